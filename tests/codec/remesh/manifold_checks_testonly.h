// The check the remeshing tests make of every mesh they produce: vertex
// rings build (each vertex's faces form one fan), edges are manifold and
// consistently oriented.
#ifndef MESHWAVE_TESTS_CODEC_REMESH_MANIFOLD_CHECKS_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_REMESH_MANIFOLD_CHECKS_TESTONLY_H_

#include <gtest/gtest.h>

#include <cstdint>

#include "meshwave/mesh.h"
#include "meshwave/mesh_stats.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::testing {

inline void ExpectOrientedManifold(const TriMesh& mesh) {
  auto rings = VertexRings::Build(static_cast<uint32_t>(mesh.positions.size()),
                                  mesh.faces);
  EXPECT_TRUE(rings.ok()) << rings.status().ToString();
  const MeshStats stats = ComputeStats(mesh);
  EXPECT_TRUE(stats.manifold);
  EXPECT_EQ(stats.inconsistently_oriented_edges, 0u);
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_REMESH_MANIFOLD_CHECKS_TESTONLY_H_
