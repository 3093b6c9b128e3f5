// End-to-end: `meshwave analyze` (JSON report, --plots CSVs) and `meshwave
// render` (a PNG of the asked size), and the PNG writer read back by an
// independent reader (signature, chunk CRCs, IHDR, inflated pixels).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>

#include "e2e/cli_runner.h"
#include "e2e/png_reader_testonly.h"
#include "png_writer.h"

namespace meshwave {
namespace {

using testing::ReadBytes;
using testing::RunCli;
using testing::TempDir;

// Every number following "key": in a JSON text (null skipped).
std::vector<double> Numbers(const std::string& json, const std::string& key) {
  std::vector<double> out;
  const std::regex re("\"" + key + "\": (-?[0-9.eE+-]+)");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), re); it != std::sregex_iterator();
       ++it) {
    out.push_back(std::stod((*it)[1].str()));
  }
  return out;
}

TEST(AnalyzeCliTest, JsonReportHasSaneFits) {
  const auto in = testing::SampleMesh("holes.off");
  auto r = RunCli({"analyze", in.string(), "--json", "--subbands", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string& j = r.out;
  EXPECT_EQ(Numbers(j, "vertices"), std::vector<double>{4291});
  EXPECT_EQ(Numbers(j, "levels"), std::vector<double>{2});
  EXPECT_NE(j.find("\"transform\": \"butterfly\""), std::string::npos);
  EXPECT_NE(j.find("\"update\": \"constant\""), std::string::npos);
  // Two subbands x three components, each with its three fits.
  const auto samples = Numbers(j, "samples");
  ASSERT_GE(samples.size(), 6u);  // components, then MI entries
  for (int i = 0; i < 6; ++i) EXPECT_GT(samples[i], 100) << i;
  for (const std::string model : {"SL", "LM", "GG"}) {
    const auto kl = Numbers(j, model + "_kl");
    ASSERT_EQ(kl.size(), 6u) << model << "\n" << j;
    for (double v : kl) {
      EXPECT_GE(v, 0) << model;
      EXPECT_LT(v, 2) << model;
    }
  }
  // The mixture is never fitted worse than the single Laplacian it extends.
  const auto sl = Numbers(j, "SL_kl"), lm = Numbers(j, "LM_kl");
  for (size_t i = 0; i < sl.size(); ++i) EXPECT_LE(lm[i], sl[i] + 1e-3) << i;
  for (double beta : Numbers(j, "lm_beta")) {
    EXPECT_GE(beta, 0);
    EXPECT_LE(beta, 1);
  }
  const auto intra = Numbers(j, "intraband"), composite = Numbers(j, "composite");
  ASSERT_FALSE(intra.empty());
  for (size_t i = 0; i < intra.size(); ++i) {
    EXPECT_GE(intra[i], 0);
    EXPECT_LT(intra[i], 8);
    EXPECT_GE(composite[i], 0);
  }
}

TEST(AnalyzeCliTest, PlotsWritesTheCsvsAndScript) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  // gnuplot is not one of the project's dependencies: the PNGs are checked
  // only where it is installed.
  const bool gnuplot = std::system("command -v gnuplot >/dev/null 2>&1") == 0;
  std::vector<std::string> args = {"analyze", in.string(), "--plots", dir.path().string(),
                                   "--subbands", "2", "--no-mi"};
  if (!gnuplot) args.push_back("--no-gnuplot");
  auto r = RunCli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"hist_d1_c0.csv", "hist_d0_c2.csv", "dr_d1_c0.csv", "snr_gain.csv",
                           "fitted_ratios.csv", "rd.csv", "plots.gp"}) {
    const std::string text = ReadBytes(dir / name);
    EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 2) << name;
  }
  const std::string rd = ReadBytes(dir / "rd.csv");
  for (const char* coder : {"3xc", "sim", "pgc"}) {
    EXPECT_NE(rd.find(coder), std::string::npos) << coder << "\n" << rd.substr(0, 300);
  }
  const std::string gp = ReadBytes(dir / "plots.gp");
  for (const char* png : {"histograms.png", "dr.png", "snr_gain.png", "rd.png"}) {
    EXPECT_NE(gp.find(png), std::string::npos) << png;
    if (gnuplot) {
      EXPECT_TRUE(testing::ReadPng(ReadBytes(dir / png)).error.empty()) << png;
    }
  }
}

TEST(RenderCliTest, WritesAPngOfTheAskedSizeColouredByError) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  auto r = RunCli({"render", in.string(), (dir / "a.png").string(), "--width", "320",
                   "--height", "200", "--reference", in.string(), "--view", "30,20"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto png = testing::ReadPng(ReadBytes(dir / "a.png"));
  ASSERT_TRUE(png.error.empty()) << png.error;
  EXPECT_EQ(png.width, 320u);
  EXPECT_EQ(png.height, 200u);
  // Against itself every vertex has zero error: the mesh covers part of
  // the image, and every pixel that differs from the corner (background)
  // is shaded green.
  const uint8_t* bg = png.rgb.data();
  size_t mesh_pixels = 0, green = 0;
  for (size_t i = 0; i < png.rgb.size(); i += 3) {
    const uint8_t* p = png.rgb.data() + i;
    if (p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2]) continue;
    ++mesh_pixels;
    green += (p[1] > p[0] && p[1] > p[2]) ? 1 : 0;
  }
  EXPECT_GT(mesh_pixels, 320u * 200 / 20);
  EXPECT_GT(green, mesh_pixels * 95 / 100);

  r = RunCli({"render", in.string(), (dir / "b.png").string(), "--reference",
              testing::SampleMesh("elephant.off").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("vertices"), std::string::npos) << r.err;
}

TEST(PngWriterTest, WhatItWritesDecodesToTheSamePixels) {
  const int w = 7, h = 5;
  std::vector<uint8_t> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 37 + 11);
  auto bytes = cli::EncodePng(w, h, rgb);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  const auto png = testing::ReadPng(*bytes);
  ASSERT_TRUE(png.error.empty()) << png.error;
  EXPECT_EQ(png.width, 7u);
  EXPECT_EQ(png.height, 5u);
  EXPECT_EQ(png.rgb, rgb);
  // A damaged byte breaks a CRC, which the reader sees.
  std::string damaged = *bytes;
  damaged[20] ^= 1;
  EXPECT_FALSE(testing::ReadPng(damaged).error.empty());
  EXPECT_FALSE(cli::EncodePng(w, h, std::vector<uint8_t>(10)).ok());
  EXPECT_FALSE(cli::EncodePng(0, h, {}).ok());
}

}  // namespace
}  // namespace meshwave
