// `--quantizer auto` (Satti et al. 2011): the deadzone of each (subband, component)
// from the Laplacian mixture fitted to its coefficients.
#ifndef MESHWAVE_QUANT_DEADZONE_CHOICE_H_
#define MESHWAVE_QUANT_DEADZONE_CHOICE_H_

#include <span>

namespace meshwave {

// Fits the mixture by EM (analysis/laplacian_mixture.h) and maps the fitted
// sigma2 / sigma1 to a deadzone code with Satti et al. 2011's thresholds
// (DeadzoneCodeForSigmaRatio). At most 65536 evenly spaced coefficients are
// used for the fit. Fewer than 64 coefficients (or all zero): `fallback`.
int ChooseDeadzoneCode(std::span<const double> coefficients, int fallback);

}  // namespace meshwave

#endif  // MESHWAVE_QUANT_DEADZONE_CHOICE_H_
