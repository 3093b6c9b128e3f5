#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "codec/mesh/mesh_builders_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "test_data.h"

namespace meshwave {
namespace {

using ::meshwave::testing::AppendBinary;
using ::testing::HasSubstr;

constexpr char kAsciiSquare[] =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 4\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n"
    "4 0 1 2 3\n";

std::string HeaderText(const char* format, uint64_t vertices, uint64_t faces,
                       const char* coordinate_type = "float",
                       const char* face_list = "uchar int") {
  std::string h = "ply\nformat " + std::string(format) + " 1.0\n";
  h += "element vertex " + std::to_string(vertices) + "\n";
  for (const char* axis : {"x", "y", "z"}) {
    h += "property " + std::string(coordinate_type) + " " + axis + "\n";
  }
  h += "element face " + std::to_string(faces) + "\n";
  h += "property list " + std::string(face_list) +
       " vertex_indices\nend_header\n";
  return h;
}

// The tetrahedron as binary PLY in the given byte order, float + uchar/int.
std::string BinaryTetrahedron(std::endian order) {
  const char* format = order == std::endian::little ? "binary_little_endian"
                                                    : "binary_big_endian";
  TriMesh tet = testing::Tetrahedron();
  std::string out = HeaderText(format, 4, 4);
  for (const Vec3& v : tet.positions) {
    for (int axis = 0; axis < 3; ++axis) {
      AppendBinary(out, static_cast<float>(v[axis]), order);
    }
  }
  for (const Face& f : tet.faces) {
    AppendBinary<uint8_t>(out, 3, order);
    for (uint32_t i : f)
      AppendBinary<int32_t>(out, static_cast<int32_t>(i), order);
  }
  return out;
}

// Appends `value` stored as the PLY scalar type spelled `type`.
void AppendScalar(std::string& out, std::string_view type, int value,
                  std::endian order) {
  auto is = [type](const char* a, const char* b) {
    return type == a || type == b;
  };
  if (is("char", "int8")) {
    AppendBinary(out, static_cast<int8_t>(value), order);
  } else if (is("uchar", "uint8")) {
    AppendBinary(out, static_cast<uint8_t>(value), order);
  } else if (is("short", "int16")) {
    AppendBinary(out, static_cast<int16_t>(value), order);
  } else if (is("ushort", "uint16")) {
    AppendBinary(out, static_cast<uint16_t>(value), order);
  } else if (is("int", "int32")) {
    AppendBinary(out, static_cast<int32_t>(value), order);
  } else if (is("uint", "uint32")) {
    AppendBinary(out, static_cast<uint32_t>(value), order);
  } else if (is("float", "float32")) {
    AppendBinary(out, static_cast<float>(value), order);
  } else {
    AppendBinary(out, static_cast<double>(value), order);
  }
}

Status ParseStatus(std::string_view bytes) {
  return ParseMesh(bytes, MeshFormat::kPly, "test.ply").status();
}

TEST(PlyReaderTest, ReadsAsciiAndFanTriangulatesQuads) {
  Result<TriMesh> mesh =
      ParseMesh(kAsciiSquare, MeshFormat::kPly, "square.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  ASSERT_EQ(mesh->positions.size(), 4u);
  EXPECT_EQ(mesh->positions[2], Vec3(1, 1, 0));
  ASSERT_EQ(mesh->faces.size(), 2u);
  EXPECT_EQ(mesh->faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(mesh->faces[1], (Face{0, 2, 3}));
}

TEST(PlyReaderTest, ReadsBinaryLittleAndBigEndianAlike) {
  TriMesh tet = testing::Tetrahedron();
  for (std::endian order : {std::endian::little, std::endian::big}) {
    Result<TriMesh> mesh =
        ParseMesh(BinaryTetrahedron(order), MeshFormat::kPly, "t.ply");
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->positions, tet.positions);
    EXPECT_EQ(mesh->faces, tet.faces);
  }
}

TEST(PlyReaderTest, ReadsBigEndianFileFromCorpus) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/tetrahedron_big_endian.ply"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions, testing::Tetrahedron().positions);
  EXPECT_EQ(mesh->faces, testing::Tetrahedron().faces);
}

// Every scalar type and alias, for coordinates, in both encodings.
TEST(PlyReaderTest, ReadsCoordinatesOfEveryScalarType) {
  for (const char* type : {"char", "uchar", "short", "ushort", "int", "uint",
                           "float", "double", "int8", "uint8", "int16",
                           "uint16", "int32", "uint32", "float32", "float64"}) {
    SCOPED_TRACE(type);
    std::string ascii =
        HeaderText("ascii", 3, 1, type) + "1 2 3\n4 5 6\n7 8 9\n3 0 1 2\n";
    Result<TriMesh> from_ascii = ParseMesh(ascii, MeshFormat::kPly, "a.ply");
    ASSERT_TRUE(from_ascii.ok()) << from_ascii.status().ToString();
    EXPECT_EQ(from_ascii->positions[2], Vec3(7, 8, 9));

    std::string binary = HeaderText("binary_big_endian", 3, 1, type);
    for (int value = 1; value <= 9; ++value) {
      AppendScalar(binary, type, value, std::endian::big);
    }
    AppendBinary<uint8_t>(binary, 3, std::endian::big);
    for (int32_t i : {0, 1, 2})
      AppendBinary<int32_t>(binary, i, std::endian::big);
    Result<TriMesh> from_binary = ParseMesh(binary, MeshFormat::kPly, "b.ply");
    ASSERT_TRUE(from_binary.ok()) << from_binary.status().ToString();
    EXPECT_EQ(from_binary->positions[1], Vec3(4, 5, 6));
  }
}

template <class Count, class Index>
std::string TriangleWithListTypes(const char* list_types) {
  std::string out =
      HeaderText("binary_little_endian", 3, 1, "float", list_types);
  for (int i = 0; i < 9; ++i)
    AppendBinary<float>(out, static_cast<float>(i), std::endian::little);
  AppendBinary<Count>(out, 3, std::endian::little);
  for (int i : {2, 1, 0})
    AppendBinary<Index>(out, static_cast<Index>(i), std::endian::little);
  return out;
}

TEST(PlyReaderTest, ReadsFaceListsOfAnyIntegerCountAndIndexType) {
  const std::string variants[] = {
      TriangleWithListTypes<uint8_t, int32_t>("uchar int"),
      TriangleWithListTypes<uint8_t, uint32_t>("uint8 uint"),
      TriangleWithListTypes<uint16_t, int16_t>("ushort short"),
      TriangleWithListTypes<uint32_t, uint16_t>("uint ushort"),
      TriangleWithListTypes<int32_t, uint8_t>("int uchar"),
      TriangleWithListTypes<int8_t, int8_t>("char char"),
  };
  for (const std::string& bytes : variants) {
    Result<TriMesh> mesh = ParseMesh(bytes, MeshFormat::kPly, "lists.ply");
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    ASSERT_EQ(mesh->faces.size(), 1u);
    EXPECT_EQ(mesh->faces[0], (Face{2, 1, 0}));
  }
}

TEST(PlyReaderTest, RejectsFloatFaceIndices) {
  std::string bytes = HeaderText("ascii", 3, 1, "float", "uchar float") +
                      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  Status status = ParseStatus(bytes);
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_THAT(status.message(), HasSubstr("not integers"));
}

TEST(PlyReaderTest, SkipsExtraPropertiesAndElements) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/extra_properties_ascii.ply"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions.size(), 4u);
  EXPECT_EQ(mesh->positions[3], Vec3(0, 0, 1));
  EXPECT_EQ(mesh->faces, testing::Tetrahedron().faces);
}

TEST(PlyReaderTest, SkipsExtraBinaryListsAndElements) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment extras everywhere\n"
      "element vertex 3\nproperty uchar red\nproperty float x\n"
      "property list uchar int neighbours\nproperty float y\nproperty float z\n"
      "element face 1\nproperty uchar flags\nproperty list uchar uint "
      "vertex_index\n"
      "property float quality\nelement edge 1\nproperty int a\nproperty int b\n"
      "end_header\n";
  for (int v = 0; v < 3; ++v) {
    AppendBinary<uint8_t>(out, 255, std::endian::little);
    AppendBinary<float>(out, static_cast<float>(v), std::endian::little);
    AppendBinary<uint8_t>(out, 2, std::endian::little);
    AppendBinary<int32_t>(out, 7, std::endian::little);
    AppendBinary<int32_t>(out, 8, std::endian::little);
    AppendBinary<float>(out, 10.0f, std::endian::little);
    AppendBinary<float>(out, -1.5f, std::endian::little);
  }
  AppendBinary<uint8_t>(out, 1, std::endian::little);
  AppendBinary<uint8_t>(out, 3, std::endian::little);
  for (uint32_t i : {0u, 1u, 2u})
    AppendBinary<uint32_t>(out, i, std::endian::little);
  AppendBinary<float>(out, 0.5f, std::endian::little);
  AppendBinary<int32_t>(out, 0, std::endian::little);
  AppendBinary<int32_t>(out, 1, std::endian::little);
  Result<TriMesh> mesh = ParseMesh(out, MeshFormat::kPly, "extras.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions[2], Vec3(2, 10, -1.5));
  EXPECT_EQ(mesh->faces, (std::vector<Face>{{0, 1, 2}}));
}

TEST(PlyReaderTest, AcceptsVertexIndexName) {
  Result<TriMesh> mesh =
      ReadMesh(testing::TestData("wellformed/vertex_index_name.ply"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces.size(), 2u);
}

TEST(PlyReaderTest, RejectsIndexOutOfRangeNamingFaceAndCount) {
  std::string bytes = BinaryTetrahedron(std::endian::little);
  // Last index of face 2 is the int at the end of its record.
  size_t face2_last = bytes.size() - 13 - 4;
  int32_t bad = 40000;
  std::memcpy(bytes.data() + face2_last, &bad, 4);
  Status status = ParseStatus(bytes);
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_EQ(status.message(),
            "test.ply: face 2: vertex index 40000 out of range (4 vertices)");
}

TEST(PlyReaderTest, RejectsNegativeIndex) {
  std::string bytes = BinaryTetrahedron(std::endian::little);
  int32_t bad = -1;
  std::memcpy(bytes.data() + bytes.size() - 4, &bad, 4);
  EXPECT_THAT(ParseStatus(bytes).message(),
              HasSubstr("face 3: negative vertex index -1"));
}

TEST(PlyReaderTest, RejectsNonFiniteBinaryCoordinates) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(),
                    std::numeric_limits<float>::infinity()}) {
    std::string bytes = BinaryTetrahedron(std::endian::little);
    size_t vertex1_y = HeaderText("binary_little_endian", 4, 4).size() + 12 + 4;
    std::memcpy(bytes.data() + vertex1_y, &bad, 4);
    EXPECT_EQ(ParseStatus(bytes).message(),
              "test.ply: vertex 1: coordinate is NaN or infinite");
  }
}

TEST(PlyReaderTest, RejectsVertexCountTheFileCannotHoldBeforeAllocating) {
  std::string bytes = HeaderText("binary_little_endian", 4000000000, 1);
  bytes.append(64, '\0');
  Status status = ParseStatus(bytes);
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_THAT(status.message(),
              HasSubstr("element vertex: 4000000000 records need at least"));
}

TEST(PlyReaderTest, RejectsCountsThatOverflowSizeT) {
  std::string bytes =
      HeaderText("binary_little_endian", 3, 18446744073709551615u);
  bytes.append(36, '\0');
  EXPECT_THAT(ParseStatus(bytes).message(), HasSubstr("element face"));
  bytes = HeaderText("ascii", 3, 1) + "0 0 0\n";
  bytes.replace(bytes.find("vertex 3"), 8, "vertex 18446744073709551616");
  EXPECT_THAT(ParseStatus(bytes).message(), HasSubstr("bad element count"));
}

// Records of an element without properties take no bytes: any count is
// possible and must cost nothing.
TEST(PlyReaderTest, SkipsHugeElementsWithoutPropertiesAtOnce) {
  const std::string empty_element = "element nothing 18446744073709551615\n";
  std::string ascii = kAsciiSquare;
  ascii.insert(ascii.find("end_header"), empty_element);
  EXPECT_TRUE(ParseStatus(ascii).ok());
  std::string binary = BinaryTetrahedron(std::endian::little);
  binary.insert(binary.find("end_header"), empty_element);
  EXPECT_TRUE(ParseStatus(binary).ok());
}

// Every prefix of a valid file, each in its own allocation so that ASan sees
// any read past its end, is refused with a ParseError.
TEST(PlyReaderTest, RejectsEveryTruncation) {
  for (std::endian order : {std::endian::little, std::endian::big}) {
    const std::string whole = BinaryTetrahedron(order);
    for (size_t n = 0; n < whole.size(); ++n) {
      std::string prefix = whole.substr(0, n);
      Status status = ParseStatus(prefix);
      ASSERT_EQ(status.code(), StatusCode::kParseError) << "prefix " << n;
    }
  }
  const std::string ascii = kAsciiSquare;
  for (size_t n = 0; n + 1 < ascii.size(); ++n) {
    std::string prefix = ascii.substr(0, n);
    ASSERT_EQ(ParseStatus(prefix).code(), StatusCode::kParseError)
        << "prefix " << n;
  }
}

TEST(PlyReaderTest, RejectsBytesAfterTheLastElement) {
  std::string bytes = BinaryTetrahedron(std::endian::little) + "junk";
  EXPECT_THAT(ParseStatus(bytes).message(), HasSubstr("4 unexpected bytes"));
  EXPECT_TRUE(ParseStatus(BinaryTetrahedron(std::endian::little) + "\n").ok());
}

TEST(PlyReaderTest, RejectsPolygonsWithFewerThanThreeCorners) {
  for (int corners : {0, 1, 2}) {
    std::string bytes = HeaderText("ascii", 3, 1) + "0 0 0\n1 0 0\n0 1 0\n" +
                        std::to_string(corners);
    for (int i = 0; i < corners; ++i) {
      bytes += ' ';  // not `" " + to_string`: GCC 12 -Wrestrict false positive
      bytes += std::to_string(i);
    }
    EXPECT_THAT(ParseStatus(bytes + "\n").message(),
                HasSubstr("face 0: polygon with " + std::to_string(corners) +
                          " corners"));
  }
}

TEST(PlyReaderTest, RejectsAsciiValueOutsideItsType) {
  std::string bytes =
      HeaderText("ascii", 3, 1, "uchar") + "0 0 0\n1 0 0\n0 1 300\n3 0 1 2\n";
  EXPECT_EQ(ParseStatus(bytes).message(),
            "test.ply: line 12: vertex 2: 300 does not fit in uchar");
}

TEST(PlyReaderTest, RejectsHeaderErrorsNamingTheLine) {
  std::string bytes = kAsciiSquare;
  bytes.replace(bytes.find("float y"), 7, "float128 y");
  EXPECT_EQ(ParseStatus(bytes).message(),
            "test.ply: line 5: unknown property type \"float128\"");
  EXPECT_EQ(ParseStatus("plx\n").message(),
            "test.ply: line 1: not a PLY file (no \"ply\" magic)");
}

TEST(PlyReaderTest, AcceptsCrLfLineEnds) {
  std::string bytes;
  for (char c : std::string(kAsciiSquare)) {
    if (c == '\n') bytes += '\r';
    bytes += c;
  }
  Result<TriMesh> mesh = ParseMesh(bytes, MeshFormat::kPly, "crlf.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->faces.size(), 2u);
}

}  // namespace
}  // namespace meshwave
