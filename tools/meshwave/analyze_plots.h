// The files `meshwave analyze --plots DIR` writes: CSV tables of the
// analysis and one gnuplot script that turns them into PNG figures
// (histograms with the fitted models, D-R curves, the quantiser SNR gaps of
// Satti et al. 2011, Fig. 7; rate-distortion curves of the coders).
#ifndef MESHWAVE_TOOLS_ANALYZE_PLOTS_H_
#define MESHWAVE_TOOLS_ANALYZE_PLOTS_H_

#include <string>
#include <vector>

#include "meshwave/analysis.h"
#include "meshwave/rate_distortion.h"
#include "meshwave/status.h"

namespace meshwave::cli {

// One curve of Satti et al. 2011, Fig. 7: SNR gain over UEQ against sigma2/sigma1.
struct SnrGainCurve {
  double z = 1;
  std::vector<double> ratio, gain_db;
};

// A rate-distortion curve measured outside meshwave (Draco), read from a
// CSV with a header line and columns bpv,psnr_db.
struct ExternalRdCurve {
  std::string name;
  std::vector<double> bpv, psnr_db;
};
Result<ExternalRdCurve> ReadExternalRdCurve(const std::string& path, std::string name);

struct PlotInputs {
  std::string title;  // the mesh's name
  const PyramidAnalysis* analysis = nullptr;
  std::vector<SnrGainCurve> snr_gain;
  std::vector<RdCurve> rd;
  std::vector<ExternalRdCurve> external_rd;
};

// Writes the CSVs and DIR/plots.gp into `dir` (created if missing), then
// runs gnuplot on it when `run_gnuplot` (an error if gnuplot is missing or
// fails). Returns the PNG files written (or to be written by the script).
Result<std::vector<std::string>> WritePlots(const std::string& dir, const PlotInputs& in,
                                            bool run_gnuplot);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_ANALYZE_PLOTS_H_
