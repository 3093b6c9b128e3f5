#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "test_data.h"

namespace meshwave {
namespace {

using ::testing::HasSubstr;

Result<TriMesh> ParseOff(std::string_view text) {
  return ParseMesh(text, MeshFormat::kOff, "a.off");
}

const std::vector<Face> kTetrahedronFaces = {
    {0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TEST(OffReaderTest, ReadsCommentsAndColours) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/comments_and_colours.off"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0),
                                                Vec3(0, 1, 0), Vec3(0, 0, 1)}));
  EXPECT_EQ(mesh->faces, kTetrahedronFaces);
}

TEST(OffReaderTest, ReadsCountsOnTheKeywordLineAndPolygons) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/counts_on_keyword_line_crlf.off"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces, (std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}}));
}

TEST(OffReaderTest, ReadsNoffIgnoringNormals) {
  Result<TriMesh> mesh = ReadMesh(testing::TestData("wellformed/normals.off"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions[1], Vec3(1, 0, 0));
}

TEST(OffReaderTest, AcceptsAMissingKeyword) {
  Result<TriMesh> mesh = ParseOff("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces.size(), 1u);
}

TEST(OffReaderTest, ReadsTheProjectSampleMeshes) {
  for (const char* name : {"elephant.off", "holes.off"}) {
    Result<TriMesh> mesh = ReadMesh(testing::SampleMesh(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_GT(mesh->faces.size(), 500u);
  }
  Result<TriMesh> elephant = ReadMesh(testing::SampleMesh("elephant.off"));
  ASSERT_TRUE(elephant.ok());
  EXPECT_EQ(elephant->positions.size(), 2775u);
  EXPECT_EQ(elephant->faces.size(), 5558u);
}

TEST(OffReaderTest, RejectsIndexOutOfRangeNamingTheLine) {
  EXPECT_EQ(
      ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").status().message(),
      "a.off: line 6: vertex index 3 out of range (3 vertices)");
  EXPECT_THAT(
      ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").status().message(),
      HasSubstr("line 6: vertex index -1 out of range"));
}

TEST(OffReaderTest, RejectsCountsTheFileCannotHold) {
  Status status = ParseOff("OFF\n4000000000 1 0\n0 0 0\n").status();
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_THAT(status.message(),
              HasSubstr("line 2: 4000000000 vertices and 1 faces cannot fit"));
  EXPECT_THAT(ParseOff("OFF\n3 18446744073709551615 0\n").status().message(),
              HasSubstr("line 2:"));
  EXPECT_THAT(ParseOff("OFF\n5000000000 1 0\n").status().message(),
              HasSubstr("more than 32-bit indices"));
}

TEST(OffReaderTest, RejectsTruncatedFiles) {
  const std::string whole = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  for (size_t n = 0; n + 2 < whole.size(); ++n) {
    std::string prefix = whole.substr(0, n);
    EXPECT_EQ(ParseOff(prefix).status().code(), StatusCode::kParseError) << prefix;
  }
}

TEST(OffReaderTest, RejectsBadNumbersAndShortFaces) {
  EXPECT_EQ(ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1.2.3 0\n3 0 1 2\n")
                .status()
                .message(),
            "a.off: line 5: bad number \"1.2.3\"");
  EXPECT_THAT(ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1  # short\n")
                  .status()
                  .message(),
              HasSubstr("line 6: face with 2 corners"));
  EXPECT_THAT(
      ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n").status().message(),
      HasSubstr("line 6: face has 3 of its 4 indices"));
}

TEST(OffReaderTest, RejectsUnsupportedVariants) {
  EXPECT_THAT(ParseOff("OFF BINARY\n").status().message(),
              HasSubstr("binary OFF"));
  EXPECT_THAT(ParseOff("4OFF\n1 0 0\n").status().message(),
              HasSubstr("not supported"));
  EXPECT_THAT(ParseOff("PLY\n").status().message(),
              HasSubstr("line 1: not an OFF file"));
}

}  // namespace
}  // namespace meshwave
