// meshwave analyze IN [--json] [--plots DIR]: the statistical
// analysis of one mesh's wavelet coefficients (sections 3-4): model fits
// with KL and ME(%) (Tables 1-2), the deadzone `--quantizer auto` would
// choose, mutual information (Table 3), and with --plots the figures.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "analyze_plots.h"
#include "cli_util.h"
#include "commands.h"
#include "meshwave/analysis.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/rate_distortion.h"
#include "meshwave/semiregular_input.h"
#include "meshwave/stream_limits.h"
#include "meshwave/wavelet.h"

namespace meshwave::cli {
namespace {

struct AnalyzeArgs {
  std::string in, plots, draco_csv, predictor = "butterfly", update = "";
  int levels = -1;
  int precision = 16;
  int subbands = 5;
  bool json = false, no_mi = false, no_gnuplot = false, rd = false;
};

const char* kZ[4] = {"2 (SAQ)", "1 (UEQ)", "1.5", "2.5"};

// Mean of f over the analysed components that `pick` selects (NaN if none).
template <typename Pick, typename F>
double Mean(const PyramidAnalysis& a, Pick pick, F f) {
  double sum = 0;
  int n = 0;
  for (const ComponentAnalysis& c : a.components) {
    if (!pick(c)) continue;
    sum += f(c);
    ++n;
  }
  return n ? sum / n : NAN;
}

void PrintTables(const AnalyzeArgs& args, const SemiRegularMesh& mesh,
                 const PyramidAnalysis& a) {
  std::printf("%s: %zu vertices, %d levels; %s/%s, local frames\n", args.in.c_str(),
              mesh.positions.size(), mesh.levels(), args.predictor.c_str(),
              args.update.c_str());
  std::printf("\nPer subband and component: fits (KL in bits, ME in %%), LM parameters, auto deadzone z\n");
  std::printf("%4s %4s %8s | %7s %6s | %7s %6s | %7s %6s | %6s %10s %6s | %5s %9s\n", "band",
              "comp", "samples", "SL KL", "ME", "LM KL", "ME", "GG KL", "ME", "beta",
              "s2/s1", "alpha", "EM it", "z");
  for (const ComponentAnalysis& c : a.components) {
    std::printf("%4d %4d %8zu | %7.4f %6.2f | %7.4f %6.2f | %7.4f %6.2f | %6.3f %10.2f %6.3f | %5d %9s\n",
                c.subband, c.component, c.samples, c.fit[0].kl_bits, c.fit[0].me_percent,
                c.fit[1].kl_bits, c.fit[1].me_percent, c.fit[2].kl_bits, c.fit[2].me_percent,
                c.lm_beta, c.lm_sigma2 / c.lm_sigma1, c.gg_alpha, c.em_iterations,
                kZ[c.auto_deadzone]);
  }
  std::printf("\nAs Satti et al. 2011, Table 1 (mean over the subbands above): KL (ME %%)\n");
  std::printf("%-10s %18s %18s %18s\n", "component", "SL", "LM", "GG");
  const char* names[3] = {"normal", "tangent 1", "tangent 2"};
  for (int comp = 0; comp < 3; ++comp) {
    std::printf("%-10s", names[comp]);
    for (int m = 0; m < 3; ++m) {
      const auto pick = [comp](const ComponentAnalysis& c) { return c.component == comp; };
      std::printf("   %7.4f (%6.2f)",
                  Mean(a, pick, [m](const ComponentAnalysis& c) { return c.fit[m].kl_bits; }),
                  Mean(a, pick, [m](const ComponentAnalysis& c) { return c.fit[m].me_percent; }));
    }
    std::printf("\n");
  }
  std::printf("\nAs Satti et al. 2011, Table 2 (mean over the components): KL (ME %%)\n");
  std::printf("%-10s %18s %18s %18s\n", "subband", "SL", "LM", "GG");
  int last = -1;
  for (const ComponentAnalysis& c0 : a.components) {
    if (c0.subband == last) continue;
    last = c0.subband;
    std::printf("d^%-8d", last);
    for (int m = 0; m < 3; ++m) {
      const auto pick = [last](const ComponentAnalysis& c) { return c.subband == last; };
      std::printf("   %7.4f (%6.2f)",
                  Mean(a, pick, [m](const ComponentAnalysis& c) { return c.fit[m].kl_bits; }),
                  Mean(a, pick, [m](const ComponentAnalysis& c) { return c.fit[m].me_percent; }));
    }
    std::printf("\n");
  }
  if (!a.mutual_information.empty()) {
    std::printf(
        "\nAs Satti et al. 2011, Table 3: mutual information [bits], mean over "
        "components\n");
    std::printf("%-10s %8s %10s %10s %10s\n", "subband", "samples", "intraband", "interband",
                "composite");
    double sums[3] = {0, 0, 0};
    int bands = 0;
    for (size_t i = 0; i + 2 < a.mutual_information.size(); i += 3) {
      double m[3] = {0, 0, 0};
      for (size_t k = i; k < i + 3; ++k) {
        m[0] += a.mutual_information[k].intraband / 3;
        m[1] += a.mutual_information[k].interband / 3;
        m[2] += a.mutual_information[k].composite / 3;
      }
      std::printf("d^%-8d %8zu %10.4f %10.4f %10.4f\n", a.mutual_information[i].subband,
                  a.mutual_information[i].samples, m[0], m[1], m[2]);
      for (int q = 0; q < 3; ++q) sums[q] += m[q];
      ++bands;
    }
    std::printf("%-10s %8s %10.4f %10.4f %10.4f\n", "mean", "", sums[0] / bands,
                sums[1] / bands, sums[2] / bands);
  }
}

std::string J(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void PrintJsonReport(const AnalyzeArgs& args, const SemiRegularMesh& mesh, bool remeshed,
                     const PyramidAnalysis& a, const std::vector<RdCurve>& rd) {
  std::string o = "{\n  \"input\": \"" + args.in + "\",\n";
  o += "  \"remeshed\": " + std::string(remeshed ? "true" : "false") + ",\n";
  o += "  \"vertices\": " + std::to_string(mesh.positions.size()) + ",\n";
  o += "  \"levels\": " + std::to_string(mesh.levels()) + ",\n";
  o += "  \"transform\": \"" + args.predictor + "\",\n  \"update\": \"" + args.update + "\",\n";
  o += "  \"components\": [";
  for (size_t i = 0; i < a.components.size(); ++i) {
    const ComponentAnalysis& c = a.components[i];
    o += i ? ",\n    {" : "\n    {";
    o += "\"subband\": " + std::to_string(c.subband) + ", \"component\": " +
         std::to_string(c.component) + ", \"samples\": " + std::to_string(c.samples) +
         ", \"sigma\": " + J(c.sigma) + ", \"sl_sigma\": " + J(c.sl_sigma) +
         ", \"lm_beta\": " + J(c.lm_beta) + ", \"lm_sigma1\": " + J(c.lm_sigma1) +
         ", \"lm_sigma2\": " + J(c.lm_sigma2) + ", \"em_iterations\": " +
         std::to_string(c.em_iterations) + ", \"gg_sigma\": " + J(c.gg_sigma) +
         ", \"gg_alpha\": " + J(c.gg_alpha) + ", \"auto_deadzone\": " +
         std::to_string(c.auto_deadzone);
    for (int m = 0; m < 3; ++m) {
      const std::string n = SourceModelName(kSourceModels[m]);
      o += ", \"" + n + "_kl\": " + J(c.fit[m].kl_bits) + ", \"" + n + "_me\": " +
           J(c.fit[m].me_percent);
    }
    o += "}";
  }
  o += "\n  ],\n  \"mutual_information\": [";
  for (size_t i = 0; i < a.mutual_information.size(); ++i) {
    const MutualInformationResult& m = a.mutual_information[i];
    o += i ? ",\n    {" : "\n    {";
    o += "\"subband\": " + std::to_string(m.subband) + ", \"component\": " +
         std::to_string(m.component) + ", \"samples\": " + std::to_string(m.samples) +
         ", \"intraband\": " + J(m.intraband) + ", \"interband\": " + J(m.interband) +
         ", \"composite\": " + J(m.composite) + "}";
  }
  o += "\n  ],\n  \"rd\": [";
  for (size_t i = 0; i < rd.size(); ++i) {
    o += i ? ",\n    {" : "\n    {";
    o += "\"coder\": \"" + std::string(RdCoderName(rd[i].coder)) + "\", \"psnr_at_bpv\": [";
    for (size_t k = 0; k < kRdTableBpv.size(); ++k) {
      o += (k ? ", " : "") + J(PsnrAtBpv(rd[i], kRdTableBpv[k]));
    }
    o += "]}";
  }
  o += "\n  ]\n}\n";
  std::fputs(o.c_str(), stdout);
}

std::vector<SnrGainCurve> SnrGainCurves() {
  std::vector<SnrGainCurve> out;
  for (double z : {1.0, 1.5, 2.0, 2.5, 3.0}) {
    SnrGainCurve c;
    c.z = z;
    for (int i = 0; i <= 48; ++i) {
      const double ratio = std::pow(10.0, 3.3 * i / 48);  // 1 .. 2000
      c.ratio.push_back(ratio);
      c.gain_db.push_back(EdsqSnrGain(0.9, ratio, z));
    }
    out.push_back(std::move(c));
  }
  return out;
}

Status Run(const AnalyzeArgs& given) {
  EncodeOptions options;
  MW_RETURN_IF_ERROR(
      ApplyTransformOptions(given.predictor, given.update, given.precision, options));
  if (options.transform.predictor == Predictor::kSawt) {
    return InvalidArgument(
        "analyze does not run sawt (its filters are chosen inside the encoder); "
        "measure it with `meshwave rd --transform sawt`");
  }
  AnalyzeArgs args = given;  // with the update resolved, as the report prints it
  args.update = UpdateWeightsName(options.transform.update);
  MW_ASSIGN_OR_RETURN(TriMesh raw, ReadMesh(args.in));
  SemiRegularInputOptions in_options;
  in_options.levels = args.levels;
  MW_ASSIGN_OR_RETURN(SemiRegularInput input, ToSemiRegular(std::move(raw), in_options));
  if (input.remeshed) {
    std::cerr << args.in << ": not semi-regular; remeshed to " << input.levels
              << " levels, " << input.finest_vertices << " vertices\n";
  }
  const SemiRegularMesh& mesh = input.mesh;
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(mesh.hierarchy, options.transform));
  const Pyramid pyramid = transform.Forward(mesh.positions);
  AnalysisOptions a_options;
  a_options.subbands = args.subbands;
  a_options.mutual_information = !args.no_mi;
  MW_ASSIGN_OR_RETURN(PyramidAnalysis analysis, AnalyzePyramid(pyramid, a_options));

  std::vector<RdCurve> rd;
  if (args.rd || !args.plots.empty()) {
    for (RdCoder coder : {RdCoder::k3xC, RdCoder::kSim, RdCoder::kPgc}) {
      auto curve = MeasureRdCurve(mesh, coder, options);
      if (!curve.ok()) return curve.status().WithContext(RdCoderName(coder));
      rd.push_back(*std::move(curve));
    }
  }
  if (!args.plots.empty()) {
    PlotInputs plots;
    plots.title = std::filesystem::path(args.in).stem().string();
    plots.analysis = &analysis;
    plots.snr_gain = SnrGainCurves();
    plots.rd = rd;
    if (!args.draco_csv.empty()) {
      MW_ASSIGN_OR_RETURN(ExternalRdCurve draco, ReadExternalRdCurve(args.draco_csv, "draco"));
      plots.external_rd.push_back(std::move(draco));
    }
    MW_ASSIGN_OR_RETURN(std::vector<std::string> pngs,
                        WritePlots(args.plots, plots, !args.no_gnuplot));
    for (const auto& p : pngs) std::cerr << (args.no_gnuplot ? "script for " : "wrote ") << p << "\n";
  }
  if (args.json) {
    PrintJsonReport(args, mesh, input.remeshed, analysis, rd);
  } else {
    PrintTables(args, mesh, analysis);
    if (!rd.empty()) {
      std::printf("\nPSNR [dB] at bpv (base excluded):");
      for (double b : kRdTableBpv) std::printf(" %6.2f", b);
      std::printf("\n");
      for (const RdCurve& c : rd) {
        std::printf("%-33s", RdCoderName(c.coder));
        for (double b : kRdTableBpv) std::printf(" %6.2f", PsnrAtBpv(c, b));
        std::printf("\n");
      }
    }
  }
  return Status::Ok();
}

}  // namespace

void AddAnalyzeCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "analyze", "Statistical analysis of a mesh's wavelet coefficients (as Satti et al. 2011): "
                 "SL/LM/GG fits with KL and ME, deadzone choice, mutual information; "
                 "--plots writes CSVs and PNG figures (gnuplot)");
  cmd->add_option("in", args->in, "Mesh file (.ply, .obj, .off, .glb, .gltf); irregular meshes are remeshed")
      ->required();
  cmd->add_flag("--json", args->json, "Print the report as JSON");
  cmd->add_option("--plots", args->plots,
                  "Write CSVs, plots.gp and PNGs (histograms, D-R, SNR gain, RD) to DIR");
  cmd->add_flag("--no-gnuplot", args->no_gnuplot, "With --plots: write the script, do not run it");
  cmd->add_option("--draco-csv", args->draco_csv,
                  "With --plots: add a Draco RD curve from a CSV (header, then bpv,psnr_db)");
  cmd->add_flag("--rd", args->rd, "Also measure the 3xC/SIM/PGC rate-distortion curves");
  cmd->add_option("--subbands", args->subbands, "How many of the finest subbands to model")
      ->check(CLI::Range(1, kMaxStreamLevels))
      ->capture_default_str();
  cmd->add_flag("--no-mi", args->no_mi, "Skip the mutual information estimates");
  AddTransformOptions(cmd, args->predictor, args->update, args->levels, args->precision);
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("analyze", s);
  });
}

}  // namespace meshwave::cli
