// AnalyzePyramid: the per-subband fits and estimates behind `meshwave
// analyze` (Satti et al. 2011, Tables 1-3, Figs. 5-6).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "analysis/divergence.h"
#include "analysis/edsq_distortion_rate.h"
#include "analysis/generalized_gaussian.h"
#include "analysis/laplacian_mixture.h"
#include "analysis/mutual_information.h"
#include "analysis/wavelet_dependencies.h"
#include "meshwave/analysis.h"

namespace meshwave {
namespace {

// D-R curves: finest step sigma / 32 (about 6 bits per coefficient), then
// doubling until everything falls in the deadzone.
constexpr int kDrLevels = 14;

std::vector<DrSample> Samples(const std::vector<DrPoint>& points) {
  std::vector<DrSample> out;
  for (size_t n = 0; n < points.size(); ++n) {
    out.push_back({static_cast<int>(n), points[n].rate, points[n].distortion});
  }
  return out;
}

ComponentAnalysis AnalyzeComponent(const std::vector<double>& x, int j, int c) {
  ComponentAnalysis a;
  a.subband = j;
  a.component = c;
  a.samples = x.size();
  double sq = 0;
  for (double v : x) sq += v * v;
  a.sigma = std::sqrt(sq / static_cast<double>(x.size()));

  const Histogram hist = BuildHistogram(x);
  const Laplacian sl = FitLaplacian(x);
  const MixtureFit lm = FitLaplacianMixture(x, hist);
  const GgFit gg = FitGeneralizedGaussian(x, hist);
  a.sl_sigma = sl.Sigma();
  a.lm_beta = lm.model.beta();
  a.lm_sigma1 = lm.model.component1().Sigma();
  a.lm_sigma2 = lm.model.component2().Sigma();
  a.em_iterations = lm.iterations;
  a.gg_sigma = gg.model.Sigma();
  a.gg_alpha = gg.model.alpha();
  a.auto_deadzone = DeadzoneCodeForSigmaRatio(a.lm_sigma2 / a.lm_sigma1);

  const std::array<const SourceModel*, 3> models = {&sl, &lm.model, &gg.model};
  for (size_t i = 1; i + 1 < hist.probability.size(); ++i) {
    a.bin_centre.push_back(hist.Centre(i));
    a.observed_density.push_back(hist.probability[i] / hist.width);
    for (size_t m = 0; m < 3; ++m) {
      a.model_density[m].push_back(
          models[m]->SignedMass(hist.Lower(i), hist.Upper(i)) / hist.width);
    }
  }

  const double step0 = (a.sigma > 0 ? a.sigma : 1.0) / 32;
  const auto observed = DrCurve(step0, 0.0, kDrLevels, [&](const EdsqLevel& q) {
    return ObservedDistortionRate(x, q);
  });
  const auto sl_dr = DrCurve(step0, 0.0, kDrLevels, [&](const EdsqLevel& q) {
    return DrPoint{LaplacianEdsqRate(sl.lambda(), q),
                   LaplacianEdsqDistortion(sl.lambda(), q)};
  });
  const auto lm_dr = DrCurve(step0, 0.0, kDrLevels, [&](const EdsqLevel& q) {
    return MixtureDistortionRate(lm.model, q);
  });
  const auto gg_dr = DrCurve(step0, 0.0, kDrLevels, [&](const EdsqLevel& q) {
    return ModelDistortionRate(gg.model, q);
  });
  a.observed_dr = Samples(observed);
  const std::array<const std::vector<DrPoint>*, 3> curves = {&sl_dr, &lm_dr, &gg_dr};
  for (size_t m = 0; m < 3; ++m) {
    a.model_dr[m] = Samples(*curves[m]);
    a.fit[m].kl_bits = KlDivergence(hist, *models[m]);
    a.fit[m].me_percent = ModellingErrorPercent(*curves[m], observed);
  }
  return a;
}

}  // namespace

const char* SourceModelName(SourceModelKind kind) {
  switch (kind) {
    case SourceModelKind::kSingleLaplacian: return "SL";
    case SourceModelKind::kLaplacianMixture: return "LM";
    case SourceModelKind::kGeneralizedGaussian: return "GG";
  }
  return "?";
}

Result<PyramidAnalysis> AnalyzePyramid(const Pyramid& pyramid,
                                       const AnalysisOptions& options) {
  const int levels = pyramid.levels();
  if (levels == 0 || !pyramid.hierarchy) {
    return InvalidArgument("the mesh has no wavelet subband (0 levels)");
  }
  PyramidAnalysis out;
  const int first = std::max(0, levels - options.subbands);
  for (int j = levels - 1; j >= first; --j) {
    const auto& band = pyramid.subbands[static_cast<size_t>(j)];
    if (band.size() < 64) continue;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> x(band.size());
      for (size_t k = 0; k < band.size(); ++k) {
        x[k] = band[k][c];
        if (!std::isfinite(x[k])) {
          return InvalidArgument("subband " + std::to_string(j) +
                                 " holds a non-finite coefficient");
        }
      }
      out.components.push_back(AnalyzeComponent(x, j, c));
    }
    if (options.mutual_information && j >= 1) {
      for (int c = 0; c < 3; ++c) {
        const DependencySamples s =
            GatherDependencies(pyramid, j, c, options.mi_max_samples);
        MutualInformationResult r;
        r.subband = j;
        r.component = c;
        r.samples = s.x.size();
        r.intraband = MutualInformation(s.x, s.neighbourhood);
        r.interband = MutualInformation(s.x, s.parent);
        r.composite = MutualInformation(s.x, s.parent, s.neighbourhood);
        out.mutual_information.push_back(r);
      }
    }
  }
  return out;
}

double EdsqSnrGain(double beta, double sigma_ratio, double z, double rate_lo,
                   double rate_hi) {
  const LaplacianMixture model(beta, 1.0, sigma_ratio);
  DeltaSnrOptions options;
  options.rate_lo = rate_lo;
  options.rate_hi = rate_hi;
  return DeltaSnr(model, z, options);
}

int DeadzoneCodeForSigmaRatio(double sigma_ratio) {
  if (!(sigma_ratio >= 120)) return 1;  // UEQ (also NaN: a degenerate fit)
  if (sigma_ratio < 290) return 2;      // z = 1.5
  if (sigma_ratio < 600) return 0;      // SAQ
  return 3;                             // z = 2.5
}

}  // namespace meshwave
