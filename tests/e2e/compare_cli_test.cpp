// End-to-end: `meshwave compare` run as a user would, on the sample mesh,
// on files the test writes with known errors, and on every shared mesh.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "e2e/cli_runner.h"
#include "meshwave.pb.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "test_data.h"

namespace meshwave {
namespace {

using testing::RunCli;
using testing::TempDir;

proto::CompareReport CompareJson(const std::vector<std::string>& args) {
  std::vector<std::string> full = {"compare", "--json"};
  full.insert(full.end(), args.begin(), args.end());
  const testing::CliResult r = RunCli(full);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  proto::CompareReport report;
  const auto status =
      google::protobuf::util::JsonStringToMessage(r.out, &report);
  EXPECT_TRUE(status.ok()) << status.ToString() << "\n" << r.out;
  return report;
}

TriMesh ReadOrDie(const std::filesystem::path& path) {
  Result<TriMesh> mesh = ReadMesh(path);
  EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  return mesh.ok() ? std::move(mesh).value() : TriMesh{};
}

class CompareCliTest : public ::testing::Test {
 protected:
  const std::filesystem::path elephant_ = testing::SampleMesh("elephant.off");
  TempDir dir_;
};

TEST_F(CompareCliTest, SampleMeshAgainstItselfHasZeroError) {
  const proto::CompareReport r =
      CompareJson({elephant_.string(), elephant_.string()});
  EXPECT_EQ(r.vertices_a(), 2775u);
  EXPECT_EQ(r.vertices_b(), 2775u);
  EXPECT_EQ(r.faces_a(), 5558u);
  ASSERT_TRUE(r.has_vertex_error());
  EXPECT_EQ(r.vertex_error().matching(), "same_index");
  EXPECT_EQ(r.vertex_error().rms().absolute(), 0);
  EXPECT_EQ(r.vertex_error().rms().psnr_db(),
            std::numeric_limits<double>::infinity());
  EXPECT_LT(r.surface().hausdorff().absolute(), 1e-12 * r.diagonal());
  EXPECT_GT(r.surface().rms().psnr_db(), 200);
  // 10 samples per face by default, plus every vertex.
  EXPECT_GE(r.surface().samples_a(), 2775u + 10 * 5558u);
}

TEST_F(CompareCliTest, EveryVertexMovedByKnownAmountGivesThatError) {
  TriMesh moved = ReadOrDie(elephant_);
  const double diagonal = BoundingBox(moved.positions).Diagonal();
  const double d = 1e-3 * diagonal;
  const Vec3 offset = Vec3(1, 2, 2) / 3.0 * d;  // |offset| = d
  for (Vec3& p : moved.positions) p += offset;
  const auto moved_path = dir_ / "moved.obj";
  ASSERT_TRUE(WriteMesh(moved, moved_path).ok());

  const proto::CompareReport r =
      CompareJson({elephant_.string(), moved_path.string()});
  EXPECT_NEAR(r.diagonal(), diagonal, 1e-12 * diagonal);
  ASSERT_TRUE(r.has_vertex_error());
  const proto::VertexErrorReport& v = r.vertex_error();
  EXPECT_EQ(v.matching(), "same_index");
  EXPECT_NEAR(v.rms().absolute(), d, 1e-9 * d);
  EXPECT_NEAR(v.max().absolute(), d, 1e-9 * d);
  EXPECT_NEAR(v.rms().percent_of_diagonal(), 0.1, 1e-9);
  EXPECT_NEAR(v.rms().psnr_db(), 60, 1e-6);  // 20·log10(1000)
  // A translation by d moves the surface by at most d, and by about d
  // where the surface faces the offset.
  EXPECT_LE(r.surface().hausdorff().absolute(), d * (1 + 1e-9));
  EXPECT_GT(r.surface().hausdorff().absolute(), 0.9 * d);
  EXPECT_GT(r.surface().rms().absolute(), 0.2 * d);
}

TEST_F(CompareCliTest, ReorderedVerticesAreMatchedByNearestNeighbour) {
  const TriMesh original = ReadOrDie(elephant_);
  std::vector<uint32_t> new_index(original.positions.size());
  std::iota(new_index.begin(), new_index.end(), 0u);
  std::shuffle(new_index.begin(), new_index.end(), std::mt19937_64(5));
  TriMesh shuffled;
  shuffled.positions.resize(original.positions.size());
  for (size_t i = 0; i < original.positions.size(); ++i) {
    shuffled.positions[new_index[i]] = original.positions[i];
  }
  for (const Face& f : original.faces) {
    shuffled.faces.push_back(
        {new_index[f[0]], new_index[f[1]], new_index[f[2]]});
  }
  const auto path = dir_ / "shuffled.obj";
  ASSERT_TRUE(WriteMesh(shuffled, path).ok());

  const proto::CompareReport r =
      CompareJson({elephant_.string(), path.string()});
  ASSERT_TRUE(r.has_vertex_error());
  EXPECT_EQ(r.vertex_error().matching(), "nearest_neighbour");
  EXPECT_EQ(r.vertex_error().rms().absolute(), 0);
  EXPECT_EQ(r.vertex_error().distinct_matches(), original.positions.size());
  EXPECT_GT(r.vertex_error().same_index_rms(), 0.1 * r.diagonal());
  EXPECT_LT(r.surface().hausdorff().absolute(), 1e-12 * r.diagonal());

  const testing::CliResult text =
      RunCli({"compare", elephant_.string(), path.string()});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(
      text.out.find("vertices matched by nearest neighbour (orders differ)"),
      std::string::npos)
      << text.out;
}

TEST_F(CompareCliTest, MatchingCanBeForced) {
  // A copy with every vertex moved by a known offset, written in reverse
  // order: "index" compares the wrong vertices, "nearest" finds the offset.
  const TriMesh original = ReadOrDie(elephant_);
  const double diag = BoundingBox(original.positions).Diagonal();
  const Vec3 offset(1e-5 * diag, 0, 0);
  TriMesh reversed;
  const uint32_t n = static_cast<uint32_t>(original.positions.size());
  for (uint32_t i = 0; i < n; ++i) {
    reversed.positions.push_back(original.positions[n - 1 - i] + offset);
  }
  for (const Face& f : original.faces) {
    reversed.faces.push_back({n - 1 - f[0], n - 1 - f[1], n - 1 - f[2]});
  }
  const auto path = dir_ / "reversed.ply";
  ASSERT_TRUE(WriteMesh(reversed, path).ok());
  const proto::CompareReport nearest = CompareJson(
      {"--match", "nearest", "--min-samples", "100", elephant_.string(), path.string()});
  EXPECT_EQ(nearest.vertex_error().matching(), "nearest_neighbour");
  EXPECT_NEAR(nearest.vertex_error().rms().absolute(), offset.norm(), 1e-3 * offset.norm());
  const proto::CompareReport index = CompareJson(
      {"--match", "index", "--min-samples", "100", elephant_.string(), path.string()});
  EXPECT_EQ(index.vertex_error().matching(), "same_index");
  EXPECT_GT(index.vertex_error().rms().absolute(), 0.1 * diag);

  // Nearest matching works across different vertex counts too.
  const auto holes = testing::SampleMesh("holes.off");
  const proto::CompareReport across = CompareJson(
      {"--match", "nearest", "--min-samples", "100", elephant_.string(), holes.string()});
  ASSERT_TRUE(across.has_vertex_error());
  EXPECT_EQ(across.vertex_error().count(), original.positions.size());
  EXPECT_EQ(across.vertex_error().same_index_rms(), 0);  // not measured

  const testing::CliResult bad =
      RunCli({"compare", "--match", "closest", elephant_.string(), path.string()});
  EXPECT_NE(bad.exit_code, 0);
}

TEST_F(CompareCliTest, DifferentVertexCountsGiveOnlySurfaceDistance) {
  const auto holes = testing::SampleMesh("holes.off");
  const proto::CompareReport r =
      CompareJson({"--samples-per-face", "1", "--min-samples", "1000",
                   elephant_.string(), holes.string()});
  EXPECT_FALSE(r.has_vertex_error());
  EXPECT_NE(r.vertex_note().find("vertex counts differ"), std::string::npos);
  EXPECT_GT(r.surface().hausdorff().absolute(), 0);
  EXPECT_EQ(r.surface().hausdorff().absolute(),
            std::max(r.surface().hausdorff_ab().absolute(),
                     r.surface().hausdorff_ba().absolute()));
}

TEST_F(CompareCliTest, PrintsAlignedKeyValueLines) {
  const testing::CliResult r =
      RunCli({"compare", elephant_.string(), elephant_.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  size_t value_column = std::string::npos;
  int count = 0;
  while (std::getline(lines, line)) {
    const size_t colon = line.find(':');
    ASSERT_NE(colon, std::string::npos) << line;
    const size_t value = line.find_first_not_of(' ', colon + 1);
    ASSERT_NE(value, std::string::npos) << line;
    if (value_column == std::string::npos) value_column = value;
    EXPECT_EQ(value, value_column) << line;
    ++count;
  }
  EXPECT_GE(count, 10);
  EXPECT_NE(r.out.find("hausdorff"), std::string::npos);
  EXPECT_NE(r.out.find("PSNR inf dB"), std::string::npos) << r.out;
}

TEST_F(CompareCliTest, SameSeedGivesTheSameReport) {
  const auto holes = testing::SampleMesh("holes.off");
  const std::vector<std::string> args = {"compare",
                                         "--json",
                                         "--seed",
                                         "7",
                                         "--samples-per-face",
                                         "1",
                                         "--min-samples",
                                         "1000",
                                         elephant_.string(),
                                         holes.string()};
  const testing::CliResult first = RunCli(args);
  const testing::CliResult second = RunCli(args);
  EXPECT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.out, second.out);
}

TEST_F(CompareCliTest, MissingFileFailsNamingIt) {
  const std::string missing = (dir_ / "no_such_mesh.ply").string();
  const testing::CliResult r = RunCli({"compare", elephant_.string(), missing});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(CompareCliTest, MalformedFileFailsWithReason) {
  const auto bad = dir_ / "bad.off";
  std::ofstream(bad) << "OFF\n3 1 0\n0 0 0\n1 0 0\n";  // truncated
  const testing::CliResult r =
      RunCli({"compare", bad.string(), elephant_.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
}

TEST_F(CompareCliTest, RejectsNegativeSampleCount) {
  const testing::CliResult r = RunCli({"compare", "--samples-per-face", "-1",
                                       elephant_.string(), elephant_.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("samples-per-face"), std::string::npos) << r.err;
}

// Every shared mesh against itself: zero distance, or a refusal with a
// reason. One test per mesh, so each has its own time limit. Few samples per
// face keep this quick; the metric itself is covered by the unit tests.
class CompareCliSharedMeshTest
    : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(CompareCliSharedMeshTest, ComparesWithItselfAtZeroDistance) {
  const std::filesystem::path& mesh = GetParam();
  const testing::CliResult r =
      RunCli({"compare", "--json", "--samples-per-face", "1", mesh.string(),
              mesh.string()});
  ASSERT_EQ(r.exit_code, 0) << "refused: " << r.err;
  proto::CompareReport report;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &report).ok());
  ASSERT_TRUE(report.has_vertex_error());
  EXPECT_EQ(report.vertex_error().rms().absolute(), 0);
  EXPECT_LT(report.surface().hausdorff().absolute(), 1e-12 * report.diagonal());
}

std::string MeshTestName(
    const ::testing::TestParamInfo<std::filesystem::path>& info) {
  std::string name = info.param.filename().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, CompareCliSharedMeshTest,
                         ::testing::ValuesIn(testing::AllSharedMeshes()),
                         MeshTestName);
// A missing directory instantiates nothing: this test says so (skipped,
// or failed when the shared meshes are required).
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CompareCliSharedMeshTest);
TEST(CompareCliSharedMeshesTest, SharedMeshesArePresent) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  EXPECT_FALSE(testing::AllSharedMeshes().empty());
}

}  // namespace
}  // namespace meshwave
