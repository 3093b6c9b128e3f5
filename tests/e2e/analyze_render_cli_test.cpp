// End-to-end: `meshwave analyze` (JSON report, --plots CSVs) and `meshwave
// render` (a PNG of the asked size; textures and vertex colours drawn, grey
// with --plain or without them, error colours with --reference), and the
// render-compare's luma PSNR of decodes against the original, and the
// PNG writer read back by an independent reader (signature, chunk CRCs,
// IHDR, inflated pixels).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <utility>
#include <vector>

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

// What a render shows: pixels unlike the background (the top-left corner),
// and those of them in colour (channels more than 24 levels apart: the
// grey renders have none, every texel of the samples has some).
struct PixelCounts {
  size_t mesh = 0, chromatic = 0;
};

PixelCounts CountPixels(const testing::DecodedPng& png) {
  PixelCounts n;
  const uint8_t* bg = png.rgb.data();
  for (size_t i = 0; i < png.rgb.size(); i += 3) {
    const uint8_t* p = png.rgb.data() + i;
    if (p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2]) continue;
    ++n.mesh;
    const auto [lo, hi] = std::minmax({p[0], p[1], p[2]});
    n.chromatic += hi - lo > 24 ? 1 : 0;
  }
  return n;
}

// Renders `mesh` (plus `extra` arguments) to dir/out at 200x200 and reads
// the picture back; empty rgb (and a test failure) when either fails.
testing::DecodedPng Render(const std::filesystem::path& mesh, const TempDir& dir,
                           const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", mesh.string(), (dir / out).string(), "--width",
                                   "200", "--height", "200", "--view", "30,20"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = RunCli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  auto png = testing::ReadPng(ReadBytes(dir / out));
  EXPECT_TRUE(png.error.empty()) << out << ": " << png.error;
  return png;
}

// `mesh` renders in colour over much of its surface, and grey with --plain.
void ExpectColouredAndPlainGrey(const std::filesystem::path& mesh) {
  SCOPED_TRACE(mesh.filename().string());
  TempDir dir;
  const auto look = Render(mesh, dir, "look.png");
  const auto plain = Render(mesh, dir, "plain.png", {"--plain"});
  const PixelCounts l = CountPixels(look), p = CountPixels(plain);
  EXPECT_GT(l.mesh, 200u * 200 / 10);
  EXPECT_GT(l.chromatic, l.mesh / 2) << l.chromatic << " of " << l.mesh;
  EXPECT_GT(p.mesh, 200u * 200 / 10);
  EXPECT_EQ(p.chromatic, 0u);
  EXPECT_NE(look.rgb, plain.rgb);
}

TEST(RenderCliTest, AMeshWithoutAttributesRendersGrey) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  const auto look = Render(in, dir, "look.png");
  const PixelCounts n = CountPixels(look);
  EXPECT_GT(n.mesh, 200u * 200 / 20);
  EXPECT_EQ(n.chromatic, 0u);
  // Nothing to draw beyond the geometry: --plain gives the same pixels.
  EXPECT_EQ(Render(in, dir, "plain.png", {"--plain"}).rgb, look.rgb);
}

TEST(RenderCliTest, DrawsTheTexturedDie) {
  ExpectColouredAndPlainGrey(testing::SampleMesh("textured/die.obj"));
}

TEST(RenderCliTest, DrawsTheColouredBall) {
  ExpectColouredAndPlainGrey(testing::SampleMesh("textured/hue_ball.ply"));
}

TEST(RenderCliTest, DrawsTheGltfOfTheSamples) {
  ExpectColouredAndPlainGrey(testing::SampleMesh("textured/ring.glb"));
}

// What `decode` writes: a .glb with a base colour texture and TEXCOORD_0
// from a textured stream, and .ply and .glb with vertex colours from a
// coloured one.
TEST(RenderCliTest, DrawsTheTexturesAndColoursThatDecodeWrites) {
  TempDir dir;
  const std::pair<const char*, std::vector<const char*>> cases[] = {
      {"textured/die.obj", {"die.glb"}}, {"textured/hue_ball.ply", {"ball.ply", "ball.glb"}}};
  for (const auto& [sample, outputs] : cases) {
    const auto stream = dir / (std::string(outputs[0]) + ".mwv");
    auto r = RunCli({"encode", testing::SampleMesh(sample).string(), stream.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* out : outputs) {
      r = RunCli({"decode", stream.string(), (dir / out).string()});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      ExpectColouredAndPlainGrey(dir / out);
    }
  }
}

TEST(RenderCliTest, AMissingTextureOrFileFailsAndWritesNoPicture) {
  TempDir dir;
  for (const char* name : {"die.obj", "die.mtl"}) {
    std::filesystem::copy_file(testing::SampleMesh(std::string("textured/") + name), dir / name);
  }
  auto r = RunCli({"render", (dir / "die.obj").string(), (dir / "a.png").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("die.obj: texture die.png is missing"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--plain"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
  // The geometry alone needs no texture.
  EXPECT_EQ(CountPixels(Render(dir / "die.obj", dir, "b.png", {"--plain"})).chromatic, 0u);

  r = RunCli({"render", (dir / "none.obj").string(), (dir / "c.png").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none.obj"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.png"));

  r = RunCli({"render", (dir / "die.obj").string(), (dir / "d.png").string(), "--plain",
              "--reference", (dir / "die.obj").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--plain and --reference"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.png"));
}

// render-compare: a textured stream's decodes look closer to the original
// the more of the stream they hold; the original against itself is exact;
// an unreadable mesh of a batch is named and the others still measured.
TEST(RenderCompareCliTest, LongerPrefixesLookCloserToTheOriginal) {
  TempDir dir;
  const auto original = testing::SampleMesh("textured/die.obj");
  const auto stream = dir / "die.mwv";
  auto r = RunCli({"encode", original.string(), stream.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli({"decode", "--budget", "6000", stream.string(), (dir / "small.glb").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli({"decode", stream.string(), (dir / "complete.glb").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli({"render-compare", "--views", "4", "--size", "128", original.string(),
              (dir / "small.glb").string(), (dir / "complete.glb").string(), original.string(),
              (dir / "none.glb").string()});
  EXPECT_EQ(r.exit_code, 1);  // none.glb
  EXPECT_NE(r.err.find("none.glb"), std::string::npos) << r.err;
  const std::regex line(R"(([0-9.]+|inf)\t([0-9]+)\t(\S+))");
  std::vector<double> db;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), line);
       it != std::sregex_iterator(); ++it) {
    db.push_back((*it)[1].str() == "inf" ? INFINITY : std::stod((*it)[1].str()));
    EXPECT_GT(std::stoul((*it)[2].str()), 4u * 128 * 128 / 10) << (*it)[3].str();
  }
  ASSERT_EQ(db.size(), 3u) << r.out;
  EXPECT_GT(db[0], 10);
  EXPECT_GT(db[1], db[0] + 1);
  EXPECT_LT(db[1], 80);
  EXPECT_TRUE(std::isinf(db[2]));
}

TEST(RenderCliTest, ErrorColoursIgnoreTheTexture) {
  TempDir dir;
  const auto die = testing::SampleMesh("textured/die.obj");
  const auto png = Render(die, dir, "a.png", {"--reference", die.string()});
  // Against itself: green wherever the mesh is, no texel colours.
  size_t green = 0;
  const PixelCounts n = CountPixels(png);
  for (size_t i = 0; i < png.rgb.size(); i += 3) {
    const uint8_t* p = png.rgb.data() + i;
    green += (p[1] > p[0] + 24 && p[1] > p[2] + 24) ? 1 : 0;
  }
  EXPECT_GT(n.mesh, 200u * 200 / 10);
  EXPECT_EQ(green, n.mesh);
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
