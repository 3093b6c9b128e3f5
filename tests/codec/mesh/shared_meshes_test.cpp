// The shared development meshes read, match the statistics documented in
// their README, and survive a round trip through both writers.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "test_data.h"

namespace meshwave {
namespace {

struct Expected {
  size_t vertices;  // records in the file, unreferenced ones included
  size_t faces;
  size_t boundary_edges;
  size_t boundary_loops;
  size_t components;
  bool manifold;
  long genus;  // kUnstated when the README gives none
};
constexpr long kUnstated = -2;

// From /work/shared/data/meshes/README.md.
const std::map<std::string, Expected>& ReadmeTable() {
  static const auto* table = new std::map<std::string, Expected>{
      {"bunny_stanford_zipper.ply", {35947, 69451, 223, 5, 1, true, 0}},
      {"horse_cyberware.ply", {48485, 96966, 0, 0, 1, true, 0}},
      {"feline.ply", {49864, 99732, 0, 0, 1, true, 2}},
      {"armadillo_libigl.obj", {43243, 86482, 0, 0, 1, true, 0}},
      {"fandisk.obj", {6475, 12946, 0, 0, 1, true, 0}},
      {"igea.ply", {134345, 268686, 0, 0, 1, true, 0}},
      {"ogre.obj", {62194, 124008, 236, 12, 44, false, -1}},
      {"elephant_cartoon_sr2.obj", {4706, 9408, 0, 0, 1, true, 0}},
      {"elephant_subdiv2.ply", {44460, 88928, 0, 0, 1, true, 3}},
      {"holes_patch_sr2.ply", {4291, 8288, 304, 7, 1, true, kUnstated}},
  };
  return *table;
}

TEST(SharedMeshesTest, AllTenMeshesArePresent) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  EXPECT_EQ(testing::AllSharedMeshes().size(), ReadmeTable().size())
      << "shared meshes expected in " << testing::SharedMeshDir();
}

TEST(SharedMeshesTest, StatisticsMatchTheReadme) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  for (const std::filesystem::path& path : testing::AllSharedMeshes()) {
    const std::string name = path.filename().string();
    SCOPED_TRACE(name);
    auto row = ReadmeTable().find(name);
    ASSERT_NE(row, ReadmeTable().end()) << "not in the README table";
    const Expected& e = row->second;
    Result<TriMesh> mesh = ReadMesh(path);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->positions.size(), e.vertices);
    EXPECT_EQ(mesh->faces.size(), e.faces);
    MeshStats s = ComputeStats(*mesh);
    EXPECT_EQ(s.vertices + s.unreferenced_vertices, e.vertices);
    EXPECT_EQ(s.boundary_edges, e.boundary_edges);
    EXPECT_EQ(s.boundary_loops, e.boundary_loops);
    EXPECT_EQ(s.components, e.components);
    EXPECT_EQ(s.manifold, e.manifold);
    EXPECT_EQ(s.closed, e.manifold && e.boundary_edges == 0);
    if (e.genus != kUnstated) {
      EXPECT_EQ(s.genus, e.genus);
    }
  }
}

TEST(SharedMeshesTest, BunnyHasItsUnreferencedVertices) {
  MESHWAVE_REQUIRE_SHARED_MESH("bunny_stanford_zipper.ply");
  Result<TriMesh> mesh =
      ReadMesh(testing::SharedMesh("bunny_stanford_zipper.ply"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(ComputeStats(*mesh).unreferenced_vertices, 1113u);
}

TEST(SharedMeshesTest, OgreHasThreeNonManifoldVertices) {
  MESHWAVE_REQUIRE_SHARED_MESH("ogre.obj");
  Result<TriMesh> mesh = ReadMesh(testing::SharedMesh("ogre.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  MeshStats s = ComputeStats(*mesh);
  EXPECT_EQ(s.non_manifold_vertices, 3u);
  EXPECT_EQ(s.non_manifold_edges, 0u);
}

TEST(SharedMeshesTest, RoundTripThroughPlyAndObj) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  for (const std::filesystem::path& path : testing::AllSharedMeshes()) {
    SCOPED_TRACE(path.filename().string());
    Result<TriMesh> mesh = ReadMesh(path);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();

    Result<TriMesh> from_ply =
        ParseMesh(SerializePly(*mesh), MeshFormat::kPly, "rt.ply");
    ASSERT_TRUE(from_ply.ok()) << from_ply.status().ToString();
    EXPECT_EQ(from_ply->faces, mesh->faces);
    ASSERT_EQ(from_ply->positions.size(), mesh->positions.size());
    size_t differing = 0;
    for (size_t i = 0; i < mesh->positions.size(); ++i) {
      differing += from_ply->positions[i] !=
                   mesh->positions[i].cast<float>().cast<double>();
    }
    EXPECT_EQ(differing, 0u);

    Result<TriMesh> from_obj =
        ParseMesh(SerializeObj(*mesh), MeshFormat::kObj, "rt.obj");
    ASSERT_TRUE(from_obj.ok()) << from_obj.status().ToString();
    EXPECT_EQ(from_obj->faces, mesh->faces);
    EXPECT_TRUE(from_obj->positions == mesh->positions);
  }
}

TEST(SharedMeshesTest, ProjectSampleMeshesRead) {
  for (const char* name : {"elephant.off", "holes.off"}) {
    SCOPED_TRACE(name);
    Result<TriMesh> mesh = ReadMesh(testing::SampleMesh(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    MeshStats s = ComputeStats(*mesh);
    EXPECT_EQ(s.components, 1u);
    EXPECT_TRUE(s.manifold);
  }
}

}  // namespace
}  // namespace meshwave
