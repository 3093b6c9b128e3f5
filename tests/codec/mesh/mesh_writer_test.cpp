#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "codec/mesh/mesh_builders_testonly.h"
#include "e2e/cli_runner.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"

namespace meshwave {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A scratch directory removed at the end of each test.
class MeshWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("meshwave_writer_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST(MeshWriterFormatTest, WritesBinaryPlyWithTheAgreedHeader) {
  std::string bytes = SerializePly(testing::Tetrahedron());
  EXPECT_THAT(bytes, StartsWith("ply\nformat binary_little_endian 1.0\n"));
  EXPECT_THAT(
      bytes, HasSubstr("element vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 4\n"
                       "property list uchar int vertex_indices\nend_header\n"));
  size_t body = bytes.find("end_header\n") + 11;
  EXPECT_EQ(bytes.size() - body, 4 * 12 + 4 * 13u);
}

TEST(MeshWriterFormatTest, PlyRoundTripsToFloatPrecision) {
  TriMesh mesh = testing::Grid(3);
  mesh.positions[5] = Vec3(0.1, -1e-7, 12345.678901234);
  Result<TriMesh> back =
      ParseMesh(SerializePly(mesh), MeshFormat::kPly, "w.ply");
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->faces, mesh.faces);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_EQ(back->positions[i],
              mesh.positions[i].cast<float>().cast<double>());
  }
}

TEST(MeshWriterFormatTest, ObjRoundTripsDoublesExactly) {
  TriMesh mesh = testing::Tetrahedron();
  mesh.positions[1] = Vec3(0.1, 1.0 / 3.0, -2.2250738585072014e-308);
  mesh.positions[2] =
      Vec3(1.7976931348623157e308, 4.9406564584124654e-324, -0.0);
  std::string text = SerializeObj(mesh);
  EXPECT_THAT(
      text, HasSubstr("\nv 0.1 0.3333333333333333 -2.2250738585072014e-308\n"));
  EXPECT_THAT(text, HasSubstr("\nf 1 3 2\n"));
  Result<TriMesh> back = ParseMesh(text, MeshFormat::kObj, "w.obj");
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->positions, mesh.positions);
  EXPECT_EQ(back->faces, mesh.faces);
  EXPECT_TRUE(std::signbit(back->positions[2].z()));
}

TEST_F(MeshWriterTest, WritesAndReadsBackByExtension) {
  TriMesh mesh = testing::Grid(2);
  for (const char* name : {"grid.ply", "grid.OBJ"}) {
    std::filesystem::path path = dir_ / name;
    ASSERT_TRUE(WriteMesh(mesh, path).ok());
    Result<TriMesh> back = ReadMesh(path);
    ASSERT_TRUE(back.ok()) << back.status().ToString();
    EXPECT_EQ(back->faces, mesh.faces);
    EXPECT_EQ(back->positions, mesh.positions);
  }
  // Only the two meshes are left: no temporary files.
  EXPECT_EQ(testing::CountFilesIn(dir_), 2u);
}

TEST_F(MeshWriterTest, ReplacesAnExistingFile) {
  std::filesystem::path path = dir_ / "m.obj";
  std::ofstream(path) << "old";
  ASSERT_TRUE(WriteMesh(testing::Tetrahedron(), path).ok());
  Result<TriMesh> back = ReadMesh(path);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->faces.size(), 4u);
}

TEST_F(MeshWriterTest, FailsWithIoErrorAndLeavesNothingBehind) {
  // The target is a directory: the rename fails after the data is written.
  std::filesystem::path target = dir_ / "taken.ply";
  std::filesystem::create_directories(target / "inside");
  Status status = WriteMesh(testing::Tetrahedron(), target);
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr("taken.ply"));
  EXPECT_EQ(testing::CountFilesIn(dir_), 1u);  // only the directory

  status = WriteMesh(testing::Tetrahedron(), dir_ / "missing_dir" / "m.ply");
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr("missing_dir"));
}

TEST_F(MeshWriterTest, RefusesUnknownExtensions) {
  EXPECT_EQ(WriteMesh(testing::Tetrahedron(), dir_ / "m.stl").code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(WriteMesh(testing::Tetrahedron(), dir_ / "m.off").code(),
            StatusCode::kUnsupported);
}

TEST(MeshIoTest, GuessesFormatFromExtensionInAnyCase) {
  EXPECT_EQ(FormatFromPath("a/b.PLY").value(), MeshFormat::kPly);
  EXPECT_EQ(FormatFromPath("b.Obj").value(), MeshFormat::kObj);
  EXPECT_EQ(FormatFromPath("c.off").value(), MeshFormat::kOff);
  EXPECT_FALSE(FormatFromPath("d.stl").ok());
  EXPECT_FALSE(FormatFromPath("noextension").ok());
}

TEST(MeshIoTest, ReadMeshNamesAMissingFile) {
  Result<TriMesh> mesh = ReadMesh("/nonexistent/dir/bunny.ply");
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().code(), StatusCode::kIoError);
  EXPECT_THAT(mesh.status().message(), HasSubstr("/nonexistent/dir/bunny.ply"));
  // A missing file in a folder that exists (not a fixed name in /tmp,
  // which another program may have written).
  meshwave::testing::TempDir dir;
  EXPECT_EQ(ReadMesh(dir / "x.ply").status().code(), StatusCode::kIoError);
}

TEST(MeshIoTest, BoundingBoxCoversAllPositions) {
  Aabb box = BoundingBox({Vec3(1, -2, 3), Vec3(-1, 5, 0), Vec3(0, 0, 9)});
  EXPECT_EQ(box.min, Vec3(-1, -2, 0));
  EXPECT_EQ(box.max, Vec3(1, 5, 9));
  EXPECT_DOUBLE_EQ(box.Diagonal(), std::sqrt(4.0 + 49.0 + 81.0));
  EXPECT_EQ(BoundingBox({}).Diagonal(), 0.0);
}

}  // namespace
}  // namespace meshwave
