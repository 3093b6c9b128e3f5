#include "stream/base_mesh_decoder.h"
#include "stream/base_mesh_encoder.h"
#include "stream/base_refinement.h"
#include "stream/base_refinement_encoder.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

#include "codec/test_meshes.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "test_data.h"

namespace meshwave {
namespace {

// Encodes a mesh in transmission order and decodes it back: with R
// refinement planes, after each plane every coordinate is within half the
// cells it can still be in, and after the last exactly where R = 0 puts it.
void ExpectRoundTrip(const TriMesh& mesh, double step, uint32_t planes = 0) {
  auto chosen = ChooseTransmissionOrder(static_cast<uint32_t>(mesh.positions.size()), mesh.faces);
  ASSERT_TRUE(chosen.ok()) << chosen.status().ToString();
  const BaseMeshOrder& order = *chosen;
  std::vector<Vec3> positions(mesh.positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    positions[order.new_of_old[v]] = mesh.positions[v];
  }
  auto coded = EncodeBaseMesh(positions, order.faces, step, planes);
  ASSERT_TRUE(coded.ok()) << coded.status().ToString();
  auto decoded = DecodeBaseMesh(coded->header, 1u << 24);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->faces, order.faces);
  EXPECT_EQ(decoded->missing_planes, static_cast<int>(planes));
  for (int m = static_cast<int>(planes);; --m) {
    const double cells = std::ldexp(1.0, m);
    for (size_t v = 0; v < positions.size(); ++v) {
      EXPECT_LE((decoded->positions[v] - positions[v]).cwiseAbs().maxCoeff(),
                0.5 * step * cells * (1 + 1e-9))
          << "vertex " << v << " with " << m << " planes missing";
    }
    if (m == 0) break;
    ASSERT_TRUE(RefineBase(coded->header, m - 1,
                           EncodeBaseRefinementPlane(coded->residual, m - 1), *decoded)
                    .ok());
  }
  auto whole = EncodeBaseMesh(positions, order.faces, step, 0);
  ASSERT_TRUE(whole.ok());
  auto exact = DecodeBaseMesh(whole->header, 1u << 24);
  ASSERT_TRUE(exact.ok());
  for (size_t v = 0; v < positions.size(); ++v) {
    EXPECT_EQ(decoded->positions[v], exact->positions[v]) << "vertex " << v;
  }
}

TEST(BaseMeshCodecTest, RoundTripsSmallMeshes) {
  ExpectRoundTrip(testing::Icosahedron(), 1e-3);
  ExpectRoundTrip(testing::OpenPatch(), 1e-4);
  ExpectRoundTrip(testing::Torus(5, 7), 1e-2);
}

TEST(BaseMeshCodecTest, RefinesPlaneByPlaneToTheWholeBase) {
  ExpectRoundTrip(testing::Icosahedron(), 1e-3, 1);
  ExpectRoundTrip(testing::OpenPatch(), 1e-4, 6);
  ExpectRoundTrip(testing::Torus(5, 7), 1e-5, 20);
}

TEST(BaseMeshCodecTest, RefinementPacketsAreThreeBitsPerVertexInTurn) {
  const TriMesh ico = testing::Icosahedron();
  const BaseMeshOrder order = *ChooseTransmissionOrder(12, ico.faces);
  std::vector<Vec3> positions(12);
  for (size_t v = 0; v < 12; ++v) positions[order.new_of_old[v]] = ico.positions[v];
  auto coded = EncodeBaseMesh(positions, order.faces, 1e-4, 5);
  ASSERT_TRUE(coded.ok());
  const std::string plane4 = EncodeBaseRefinementPlane(coded->residual, 4);
  EXPECT_EQ(plane4.size(), 5u);  // 36 bits
  EXPECT_EQ(BaseRefinementBytes(12), 5u);
  // Bit 3 v + a is bit 4 of the residual of vertex v, coordinate a.
  for (size_t v = 0; v < 12; ++v) {
    for (int a = 0; a < 3; ++a) {
      const size_t k = 3 * v + static_cast<size_t>(a);
      EXPECT_EQ((static_cast<uint8_t>(plane4[k / 8]) >> (k % 8)) & 1,
                (coded->residual[v][a] >> 4) & 1);
    }
  }
  auto decoded = DecodeBaseMesh(coded->header, 1u << 24);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(RefineBase(coded->header, 3, plane4, *decoded).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(RefineBase(coded->header, 4, plane4.substr(1), *decoded).code(),
            StatusCode::kParseError);
  EXPECT_EQ(decoded->missing_planes, 5);
  ASSERT_TRUE(RefineBase(coded->header, 4, plane4, *decoded).ok());
  EXPECT_EQ(decoded->missing_planes, 4);
  const std::vector<Vec3> refined = decoded->positions;
  ForgetBaseRefinement(coded->header, *decoded);
  EXPECT_EQ(decoded->missing_planes, 5);
  EXPECT_NE(decoded->positions, refined);
  StreamHeader::BaseMesh bad = coded->header;
  bad.refinement_planes = 21;
  EXPECT_EQ(DecodeBaseMesh(bad, 1u << 24).status().code(), StatusCode::kParseError);
  EXPECT_FALSE(EncodeBaseMesh(positions, order.faces, 1e-4, 21).ok());
}

TEST(BaseMeshCodecTest, RoundTripsSampleMeshCompactly) {
  auto mesh = ReadMesh(testing::SampleMesh("elephant.off"));
  ASSERT_TRUE(mesh.ok());
  const double diag = BoundingBox(mesh->positions).Diagonal();
  ExpectRoundTrip(*mesh, diag * std::ldexp(1.0, -16));
  const BaseMeshOrder order = *ChooseTransmissionOrder(
      static_cast<uint32_t>(mesh->positions.size()), mesh->faces);
  std::vector<Vec3> positions(mesh->positions.size());
  for (size_t v = 0; v < positions.size(); ++v) positions[order.new_of_old[v]] = mesh->positions[v];
  auto coded = EncodeBaseMesh(positions, order.faces, diag * std::ldexp(1.0, -16));
  ASSERT_TRUE(coded.ok());
  // 16-bit positions and connectivity: well below the 3 x 16 + 3 x 2 x 12
  // = 120 bits per vertex of a plain fixed-width code (measured: 62.8).
  const double bits_per_vertex = 8.0 * static_cast<double>(coded->header.coded.size()) /
                                 static_cast<double>(mesh->positions.size());
  std::cout << "[base] elephant.off: " << coded->header.coded.size() << " bytes, "
            << bits_per_vertex << " bits per vertex\n";
  EXPECT_LT(bits_per_vertex, 0.6 * 120);
}

TEST(BaseMeshCodecTest, RoundTripsInconsistentOrientationAndSeveralComponents) {
  // One face of the icosahedron turned over, plus a disjoint torus.
  TriMesh mesh = testing::Icosahedron();
  std::swap(mesh.faces[3][0], mesh.faces[3][1]);
  const TriMesh torus = testing::Torus(4, 5);
  const uint32_t offset = static_cast<uint32_t>(mesh.positions.size());
  for (const Vec3& p : torus.positions) mesh.positions.push_back(p + Vec3(5, 0, 0));
  for (const Face& f : torus.faces) mesh.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  ExpectRoundTrip(mesh, 1e-3);
}

TEST(BaseMeshCodecTest, ConnectivityCostsAFewBitsPerFace) {
  // Positions on a coarse grid cost almost nothing, so the code is nearly
  // all connectivity: the traversal spends about 4 bits per face on the
  // irregular sample mesh (the corner cache it replaced spent 14).
  auto mesh = ReadMesh(testing::SampleMesh("elephant.off"));
  ASSERT_TRUE(mesh.ok());
  auto order = ChooseTransmissionOrder(static_cast<uint32_t>(mesh->positions.size()),
                                       mesh->faces);
  ASSERT_TRUE(order.ok());
  std::vector<Vec3> zeros(mesh->positions.size(), Vec3::Zero());
  auto coded = EncodeBaseMesh(zeros, order->faces, 1.0);
  ASSERT_TRUE(coded.ok());
  const double bits_per_face = 8.0 * static_cast<double>(coded->header.coded.size()) /
                               static_cast<double>(mesh->faces.size());
  std::cout << "[base] elephant.off connectivity: " << bits_per_face << " bits per face\n";
  EXPECT_LT(bits_per_face, 5.0);
}

TEST(BaseMeshCodecTest, RefusesNonManifoldAndDegenerateFaces) {
  std::vector<Face> fan = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};  // edge 0-1 in three faces
  EXPECT_EQ(ChooseTransmissionOrder(5, fan).status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(ChooseTransmissionOrder(3, {{0, 1, 1}}).ok());
  EXPECT_FALSE(ChooseTransmissionOrder(3, {{0, 1, 7}}).ok());
}

TEST(BaseMeshCodecTest, RefusesCorruptCountsAndBytes) {
  const TriMesh ico = testing::Icosahedron();
  const BaseMeshOrder order = *ChooseTransmissionOrder(12, ico.faces);
  std::vector<Vec3> positions(12);
  for (size_t v = 0; v < 12; ++v) positions[order.new_of_old[v]] = ico.positions[v];
  auto coded = EncodeBaseMesh(positions, order.faces, 1e-3);
  ASSERT_TRUE(coded.ok());
  StreamHeader::BaseMesh bad = coded->header;
  bad.vertex_count = 2000000000;
  EXPECT_FALSE(DecodeBaseMesh(bad, 1u << 24).ok());
  bad = coded->header;
  bad.face_count = 1u << 30;
  EXPECT_FALSE(DecodeBaseMesh(bad, 1u << 24).ok());
  bad = coded->header;
  bad.step = -1;
  EXPECT_FALSE(DecodeBaseMesh(bad, 1u << 24).ok());
  std::mt19937 rng(2);
  int accepted = 0;
  for (int trial = 0; trial < 500; ++trial) {
    bad = coded->header;
    std::string bytes = bad.coded;
    if (bytes.empty()) break;
    bytes[rng() % bytes.size()] ^= static_cast<char>(1 + rng() % 255);
    if (trial % 2) bytes.resize(rng() % bytes.size());
    bad.coded = bytes;
    accepted += DecodeBaseMesh(bad, 1u << 24).ok();  // must not crash
  }
  EXPECT_LT(accepted, 500);
}

TEST(RenumberBaseTest, KeepsTheSurfaceAndItsHierarchy) {
  auto sr = Subdivide(testing::OpenPatch(), 3, SubdivisionScheme::kButterfly);
  ASSERT_TRUE(sr.ok());
  const BaseMeshOrder order = *ChooseTransmissionOrder(
      sr->hierarchy->vertex_count(0), sr->hierarchy->faces(0));
  auto renumbered = RenumberBase(*sr, order.new_of_old, order.faces);
  ASSERT_TRUE(renumbered.ok()) << renumbered.status().ToString();
  // Same set of positions and, through the hierarchy, the same triangles.
  std::multiset<std::array<double, 9>> a, b;
  auto collect = [](const SemiRegularMesh& m, auto& out) {
    for (Face f : m.hierarchy->faces(m.levels())) {
      std::rotate(f.begin(), std::min_element(f.begin(), f.end(), [&](uint32_t x, uint32_t y) {
                    return m.positions[x].x() < m.positions[y].x() ||
                           (m.positions[x].x() == m.positions[y].x() &&
                            m.positions[x].y() < m.positions[y].y());
                  }),
                  f.end());
      std::array<double, 9> key;
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 3; ++k) key[3 * c + k] = m.positions[f[c]][k];
      }
      out.insert(key);
    }
  };
  collect(*sr, a);
  collect(*renumbered, b);
  EXPECT_EQ(a, b);
  EXPECT_FALSE(RenumberBase(*sr, std::vector<uint32_t>(3, 0), order.faces).ok());
}

// A permutation whose faces name other edges than the mesh has: refused
// with a message, not a wrong mesh.
TEST(RenumberBaseTest, RefusesFacesThatAreNotTheSameMesh) {
  auto sr = Subdivide(testing::OpenPatch(), 2, SubdivisionScheme::kButterfly);
  ASSERT_TRUE(sr.ok());
  const BaseMeshOrder order = *ChooseTransmissionOrder(
      sr->hierarchy->vertex_count(0), sr->hierarchy->faces(0));
  std::vector<uint32_t> swapped = order.new_of_old;
  // The base's first and last vertex trade places, the faces stay.
  std::swap(swapped.front(), swapped.back());
  auto renumbered = RenumberBase(*sr, swapped, order.faces);
  ASSERT_FALSE(renumbered.ok());
  EXPECT_NE(renumbered.status().message().find("not the same mesh"), std::string::npos)
      << renumbered.status().ToString();
}

}  // namespace
}  // namespace meshwave
