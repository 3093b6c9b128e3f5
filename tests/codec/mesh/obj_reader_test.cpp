#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "test_data.h"

namespace meshwave {
namespace {

using ::testing::HasSubstr;

Result<TriMesh> ParseObj(std::string_view text) {
  return ParseMesh(text, MeshFormat::kObj, "a.obj");
}

TEST(ObjReaderTest, ReadsVerticesAndOneBasedFaces) {
  Result<TriMesh> mesh = ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(mesh->faces, (std::vector<Face>{{0, 1, 2}}));
}

TEST(ObjReaderTest, ReadsEveryCornerFormQuadsAndNegativeIndices) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/polygons_and_corner_forms.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions.size(), 8u);
  ASSERT_EQ(mesh->faces.size(), 12u);
  EXPECT_EQ(mesh->faces[0], (Face{0, 3, 2}));  // 1/1/1 4/2/1 3/3/1 2/1/1
  EXPECT_EQ(mesh->faces[1], (Face{0, 2, 1}));
  EXPECT_EQ(mesh->faces[4], (Face{0, 1, 5}));   // -8/1 -7/2 -3/3 -4/1
  EXPECT_EQ(mesh->faces[10], (Face{3, 0, 4}));  // -5 -8 -4
  MeshStats stats = ComputeStats(*mesh);
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.genus, 0);
}

TEST(ObjReaderTest, FanTriangulatesPolygonsAndIgnoresW) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/hexagon_polygon.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces,
            (std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
  EXPECT_EQ(mesh->positions[5], Vec3(0.5, -0.866, 0));
}

TEST(ObjReaderTest, ReadsDoublesExactly) {
  Result<TriMesh> mesh = ParseObj(
      "v 0.1 -2.5e-300 1.7976931348623157e308\nv +1 2 3\nv 4 5 6\nf 1 2 3\n");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions[0], Vec3(0.1, -2.5e-300, 1.7976931348623157e308));
  EXPECT_EQ(mesh->positions[1], Vec3(1, 2, 3));
}

TEST(ObjReaderTest, AcceptsForwardReferencesWithinTheFile) {
  Result<TriMesh> mesh = ParseObj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces.size(), 1u);
}

TEST(ObjReaderTest, RejectsBadNumberNamingTheLine) {
  EXPECT_EQ(ParseObj("v 0 0 0\n# c\nv 1.2.3 0 0\n").status().message(),
            "a.obj: line 3: bad number \"1.2.3\"");
}

TEST(ObjReaderTest, RejectsNonFiniteCoordinates) {
  for (const char* bad : {"nan", "-inf", "infinity", "1e400"}) {
    Status status = ParseObj("v 0 0 " + std::string(bad) + "\n").status();
    EXPECT_EQ(status.code(), StatusCode::kParseError);
    EXPECT_THAT(status.message(), HasSubstr("a.obj: line 1:")) << bad;
  }
}

TEST(ObjReaderTest, RejectsIndicesOutOfRange) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(ParseObj(v + "f 1 2 4\n").status().message(),
            "a.obj: line 4: vertex index 4 out of range (3 vertices)");
  EXPECT_EQ(ParseObj(v + "f -1 -2 -4\n").status().message(),
            "a.obj: line 4: vertex index -4 out of range (3 vertices so far)");
  EXPECT_THAT(ParseObj(v + "f 0 1 2\n").status().message(),
              HasSubstr("line 4: vertex index 0"));
  EXPECT_THAT(ParseObj(v + "f 1 2 99999999999\n").status().message(),
              HasSubstr("line 4: vertex index 99999999999 out of range"));
}

TEST(ObjReaderTest, RejectsFacesWithFewerThanThreeCorners) {
  EXPECT_EQ(ParseObj("v 0 0 0\nv 1 0 0\nf 1 2\n").status().message(),
            "a.obj: line 3: face with 2 corners (at least 3 needed)");
  EXPECT_THAT(ParseObj("v 0 0 0\nf\n").status().message(),
              HasSubstr("face with 0 corners"));
}

TEST(ObjReaderTest, RejectsMalformedCorners) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_THAT(ParseObj(v + "f 1 2 /3\n").status().message(),
              HasSubstr("bad vertex index \"/3\""));
  EXPECT_THAT(ParseObj(v + "f 1 2 3x\n").status().message(),
              HasSubstr("bad vertex index \"3x\""));
}

TEST(ObjReaderTest, RejectsFileWithoutFaces) {
  Status status = ParseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n").status();
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_EQ(status.message(), "a.obj: no faces (3 vertices)");
}

}  // namespace
}  // namespace meshwave
