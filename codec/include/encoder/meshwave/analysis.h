// Statistical analysis of a wavelet decomposition (Satti et al. 2011): per
// subband and component, fits of the single Laplacian (SL), the Laplacian
// mixture (LM, EM as in Satti et al. 2011) and the generalized Gaussian (GG) with
// their KL divergence and D-R modelling error ME(%) (eq. 21, Tables 1-2);
// the SNR gap of embedded deadzone quantisers on the mixture (Fig. 7); and
// intraband, interband and composite mutual information (Table 3).
// Everything here reads coefficients only; nothing touches a stream.
#ifndef MESHWAVE_ANALYSIS_H_
#define MESHWAVE_ANALYSIS_H_

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "meshwave/status.h"
#include "meshwave/wavelet.h"

namespace meshwave {

enum class SourceModelKind { kSingleLaplacian, kLaplacianMixture, kGeneralizedGaussian };
inline constexpr std::array<SourceModelKind, 3> kSourceModels = {
    SourceModelKind::kSingleLaplacian, SourceModelKind::kLaplacianMixture,
    SourceModelKind::kGeneralizedGaussian};
const char* SourceModelName(SourceModelKind kind);  // "SL", "LM", "GG"

struct ModelFitQuality {
  double kl_bits = 0;     // KL(observed histogram || model)
  double me_percent = 0;  // eq. 21 between model and observed D-R curves
};

// One point of an observed or modelled D-R curve: quantiser n of the EDSQ
// family (finest step sigma / 32, SAQ), rate in bits per coefficient and
// mean squared error.
struct DrSample {
  int n = 0;
  double rate = 0;
  double distortion = 0;
};

struct ComponentAnalysis {
  int subband = 0;    // j of d^j
  int component = 0;  // 0 normal (x), 1 tangent 1 (y), 2 tangent 2 (z)
  size_t samples = 0;
  double sigma = 0;   // sample standard deviation
  double sl_sigma = 0;
  double lm_beta = 0, lm_sigma1 = 0, lm_sigma2 = 0;  // sigma1 <= sigma2
  int em_iterations = 0;
  double gg_sigma = 0, gg_alpha = 0;
  std::array<ModelFitQuality, 3> fit;  // by SourceModelKind
  // The deadzone code `--quantizer auto` gives this component (0 SAQ,
  // 1 UEQ, 2 z = 1.5, 3 z = 2.5) from lm_sigma2 / lm_sigma1.
  int auto_deadzone = 0;
  // Histogram: bin centres, observed density and the three model densities
  // (averaged over each bin), for plots.
  std::vector<double> bin_centre, observed_density;
  std::array<std::vector<double>, 3> model_density;
  // D-R curves: observed and the three models.
  std::vector<DrSample> observed_dr;
  std::array<std::vector<DrSample>, 3> model_dr;
};

struct MutualInformationResult {
  int subband = 0;  // j >= 1 (a parent is needed)
  int component = 0;
  size_t samples = 0;
  double intraband = 0;  // I(X; T), T = sum of squared neighbours, bits
  double interband = 0;  // I(X; P_X)
  double composite = 0;  // I(X; (P_X, T))
};

struct AnalysisOptions {
  // How many of the finest subbands are modelled (Satti et al. 2011's tables average
  // the five finest); subbands with fewer than 64 coefficients are skipped.
  int subbands = 5;
  bool mutual_information = true;
  // The estimator is O(N log N); larger subbands are subsampled evenly.
  size_t mi_max_samples = 200000;
};

struct PyramidAnalysis {
  std::vector<ComponentAnalysis> components;  // finest subband first
  std::vector<MutualInformationResult> mutual_information;
};

// Runs every fit and estimate on `pyramid`. Errors: a pyramid without
// subbands or with non-finite coefficients.
Result<PyramidAnalysis> AnalyzePyramid(const Pyramid& pyramid,
                                       const AnalysisOptions& options = {});

// Satti et al. 2011, Fig. 7: mean SNR gain in dB over rates [rate_lo, rate_hi] (bits
// per coefficient, log-spaced) of the EDSQ with deadzone ratio z over the
// uniform one (z = 1), for a Laplacian mixture with weight `beta` on the
// narrow component and sigma2 / sigma1 = `sigma_ratio`.
double EdsqSnrGain(double beta, double sigma_ratio, double z, double rate_lo = 0.05,
                   double rate_hi = 2.0);

// The deadzone code Satti et al. 2011 conclude a coefficient
// component with fitted ratio sigma2 / sigma1: UEQ below 120, z = 1.5 up to
// 290, SAQ up to 600, z = 2.5 above.
int DeadzoneCodeForSigmaRatio(double sigma_ratio);

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_H_
