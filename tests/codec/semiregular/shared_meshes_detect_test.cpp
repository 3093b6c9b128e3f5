// Detection on the real shared meshes: where a hierarchy is found, splitting
// its base again must give back exactly the (cleaned) input faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "test_data.h"

namespace meshwave {
namespace {

TEST(SharedMeshesDetectTest, RecoveredHierarchiesReproduceTheInput) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  int found = 0;
  for (const auto& path : testing::AllSharedMeshes()) {
    auto mesh = ReadMesh(path);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    CleanMesh(*mesh);
    auto detected = DetectSemiRegular(*mesh);
    if (!detected.ok()) {
      EXPECT_EQ(detected.status().code(), StatusCode::kNotSemiRegular);
      continue;
    }
    ++found;
    const auto& h = *detected->mesh.hierarchy;
    std::set<std::array<uint32_t, 3>> want, got;
    auto canonical = [](Face f) {
      std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
      return f;
    };
    for (const Face& f : mesh->faces) want.insert(canonical(f));
    for (Face f : h.faces(h.levels())) {
      for (uint32_t& v : f) v = detected->original_index[v];
      got.insert(canonical(f));
    }
    EXPECT_EQ(want, got) << path;
  }
  // elephant_cartoon_sr2, elephant_subdiv2, holes_patch_sr2 and ogre.
  EXPECT_EQ(found, 4);
}

}  // namespace
}  // namespace meshwave
