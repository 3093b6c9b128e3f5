#include "quant/deadzone_choice.h"

#include <vector>

#include "analysis/divergence.h"
#include "analysis/laplacian_mixture.h"
#include "meshwave/analysis.h"

namespace meshwave {

int ChooseDeadzoneCode(std::span<const double> coefficients, int fallback) {
  if (coefficients.size() < 64) return fallback;
  // The fit only needs the shape of the distribution: 2^16 samples pin
  // sigma2 / sigma1 well within Satti et al. 2011's threshold bands and keep the
  // encoder's cost to a few EM passes per component.
  constexpr size_t kMaxSamples = 65536;
  const size_t stride = (coefficients.size() + kMaxSamples - 1) / kMaxSamples;
  std::vector<double> x;
  bool any = false;
  for (size_t k = 0; k < coefficients.size(); k += stride) {
    x.push_back(coefficients[k]);
    any = any || coefficients[k] != 0;
  }
  if (!any) return fallback;
  const MixtureFit fit = FitLaplacianMixture(x, BuildHistogram(x));
  return DeadzoneCodeForSigmaRatio(fit.model.component2().Sigma() /
                                   fit.model.component1().Sigma());
}

}  // namespace meshwave
