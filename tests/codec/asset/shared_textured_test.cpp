// The shared textured and coloured meshes (../shared/data/textured) read
// as assets, against the table of their README: positions after welding,
// triangles, images and their sizes, materials; the scene's transforms
// applied (ToyCar's scale 1e-4 and quarter turn about x, the abalone's half
// turn about y); the notes name what is dropped.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <string>

#include "codec/asset/asset_checks_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "test_data.h"

namespace meshwave {
namespace {

using testing::AnyNote;

// The union of the POSITION min/max that the glTF's accessors declare.
Aabb DeclaredPositionBox(const std::filesystem::path& gltf) {
  std::ifstream in(gltf);
  const nlohmann::json doc = nlohmann::json::parse(in);
  Aabb box;
  box.min = Vec3::Constant(1e300);
  box.max = Vec3::Constant(-1e300);
  for (const auto& mesh : doc["meshes"]) {
    for (const auto& prim : mesh["primitives"]) {
      const auto& a =
          doc["accessors"][prim["attributes"]["POSITION"].get<int>()];
      for (int k = 0; k < 3; ++k) {
        box.min[k] = std::min(box.min[k], a["min"][k].get<double>());
        box.max[k] = std::max(box.max[k], a["max"][k].get<double>());
      }
    }
  }
  return box;
}

void ExpectBox(const Aabb& actual, const Vec3& min, const Vec3& max) {
  const double tolerance = 1e-6 * (max - min).norm();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(actual.min[k], min[k], tolerance) << "axis " << k;
    EXPECT_NEAR(actual.max[k], max[k], tolerance) << "axis " << k;
  }
}

TEST(SharedTexturedTest, AbaloneScan) {
  MESHWAVE_REQUIRE_SHARED_TEXTURED(
      "IridescenceAbalone/IridescenceAbalone.gltf");
  const auto path =
      testing::SharedTextured("IridescenceAbalone/IridescenceAbalone.gltf");
  const auto asset = ReadMeshAsset(path);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 3012u);  // 3,159 records welded
  EXPECT_EQ(asset->mesh.faces.size(), 6036u);
  EXPECT_EQ(asset->uv.values.size(), 3159u);
  EXPECT_TRUE(asset->color.empty());
  ASSERT_EQ(asset->materials.size(), 1u);
  const Material& m = asset->materials[0];
  EXPECT_EQ(m.base_color_texture.image, 0);
  EXPECT_EQ(m.normal_texture.image, 2);
  EXPECT_EQ(m.metallic_roughness_texture.image, 3);
  EXPECT_EQ(m.occlusion_texture.image, 3);
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.5f);
  ASSERT_EQ(asset->images.size(), 4u);
  const char* mimes[] = {"image/jpeg", "image/jpeg", "image/png", "image/jpeg"};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(asset->images[i].width, 2048u) << i;
    EXPECT_EQ(asset->images[i].height, 1024u) << i;
    EXPECT_EQ(asset->images[i].rgba.size(), 2048u * 1024 * 4) << i;
    EXPECT_EQ(asset->images[i].mime_type, mimes[i]) << i;
  }
  EXPECT_EQ(asset->images[0].name, "IridescenceAbalone_BaseColor.jpg");
  // The node turns the shell half a turn about y: x and z change sign.
  const Aabb raw = DeclaredPositionBox(path);
  ExpectBox(BoundingBox(asset->mesh.positions),
            Vec3(-raw.max.x(), raw.min.y(), -raw.max.z()),
            Vec3(-raw.min.x(), raw.max.y(), -raw.min.z()));
  EXPECT_TRUE(AnyNote(*asset, "KHR_materials_iridescence not carried"));
  EXPECT_TRUE(AnyNote(*asset, "NORMAL not carried"));
  // Closed, genus 4, one component, as the README says.
  const MeshStats stats = ComputeStats(asset->mesh);
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.components, 1u);
  EXPECT_EQ(stats.genus, 4);
}

TEST(SharedTexturedTest, ToyCarScene) {
  MESHWAVE_REQUIRE_SHARED_TEXTURED("ToyCar/ToyCar.gltf");
  const auto path = testing::SharedTextured("ToyCar/ToyCar.gltf");
  const auto asset = ReadMeshAsset(path);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 56394u);  // 77,429 records welded
  EXPECT_EQ(asset->mesh.faces.size(), 108936u);
  EXPECT_EQ(asset->uv.values.size(), 77429u);
  ASSERT_EQ(asset->materials.size(), 3u);
  EXPECT_EQ(asset->materials[0].name, "ToyCar");
  EXPECT_EQ(asset->materials[1].name, "Fabric");
  EXPECT_EQ(asset->materials[2].name, "Glass");
  std::map<uint32_t, size_t> per_material;
  for (uint32_t m : asset->face_material) ++per_material[m];
  EXPECT_EQ(per_material[0], 88837u);
  EXPECT_EQ(per_material[1], 17605u);
  EXPECT_EQ(per_material[2], 2494u);
  // The Fabric is tiled three times (KHR_texture_transform).
  const Material& fabric = asset->materials[1];
  EXPECT_FLOAT_EQ(fabric.base_color_texture.transform(0, 0), 3.0f);
  EXPECT_FLOAT_EQ(fabric.base_color_texture.transform(1, 1), 3.0f);
  EXPECT_FLOAT_EQ(fabric.occlusion_texture.transform(0, 0), 1.0f);
  EXPECT_FALSE(asset->materials[2].base_color_texture.present());
  ASSERT_EQ(asset->images.size(), 8u);
  const std::map<std::string, uint32_t> sizes = {
      {"ToyCar_normal.png", 1024},
      {"ToyCar_emissive.png", 1024},
      {"ToyCar_basecolor.png", 1024},
      {"ToyCar_occlusion_roughness_metallic.png", 1024},
      {"Fabric_normal.png", 512},
      {"Fabric_occlusion.png", 1024},
      {"Fabric_baseColor.png", 512},
      {"ToyCar_clearcoat.png", 1024}};
  for (const AssetImage& image : asset->images) {
    ASSERT_EQ(sizes.count(image.name), 1u) << image.name;
    EXPECT_EQ(image.width, sizes.at(image.name)) << image.name;
    EXPECT_EQ(image.height, sizes.at(image.name)) << image.name;
    EXPECT_EQ(image.mime_type, "image/png");
  }
  // Each mesh node scales by 1e-4 and turns a quarter about x:
  // (x, y, z) -> 1e-4 (x, -z, y).
  const Aabb raw = DeclaredPositionBox(path);
  ExpectBox(BoundingBox(asset->mesh.positions),
            1e-4 * Vec3(raw.min.x(), -raw.max.z(), raw.min.y()),
            1e-4 * Vec3(raw.max.x(), -raw.min.z(), raw.max.y()));
  for (const char* dropped :
       {"KHR_materials_clearcoat not carried",
        "KHR_materials_transmission not carried",
        "KHR_materials_sheen not carried", "8 cameras not carried"}) {
    EXPECT_TRUE(AnyNote(*asset, dropped)) << dropped;
  }
  EXPECT_EQ(ComputeStats(asset->mesh).components, 50u);
}

TEST(SharedTexturedTest, SpotObjWithMtlAndPng) {
  MESHWAVE_REQUIRE_SHARED_TEXTURED("spot/cow.obj");
  const auto path = testing::SharedTextured("spot/cow.obj");
  const auto asset = ReadMeshAsset(path);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 2930u);
  EXPECT_EQ(asset->mesh.faces.size(), 5856u);
  EXPECT_EQ(asset->uv.values.size(), 3225u);
  // Some UVs fall slightly outside [0, 1] (u >= -0.052): kept as they are.
  float min_u = 1;
  for (const auto& uv : asset->uv.values) min_u = std::min(min_u, uv.x());
  EXPECT_LT(min_u, 0.0f);
  EXPECT_GT(min_u, -0.06f);
  ASSERT_EQ(asset->materials.size(), 1u);
  EXPECT_EQ(asset->materials[0].name, "material_1");
  ASSERT_EQ(asset->images.size(), 1u);
  EXPECT_EQ(asset->images[0].name, "cow_texture.png");
  EXPECT_EQ(asset->images[0].width, 1024u);
  EXPECT_EQ(asset->images[0].height, 1024u);
  EXPECT_EQ(asset->materials[0].base_color_texture.image, 0);
  // The geometry is ReadMesh's (nothing to weld in spot).
  const auto mesh = ReadMesh(path);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(asset->mesh.positions, mesh->positions);
  EXPECT_EQ(asset->mesh.faces, mesh->faces);
}

TEST(SharedTexturedTest, GargoColouredPly) {
  MESHWAVE_REQUIRE_SHARED_TEXTURED("gargo/gargo.ply");
  const auto path = testing::SharedTextured("gargo/gargo.ply");
  const auto asset = ReadMeshAsset(path);
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_EQ(asset->mesh.positions.size(), 25002u);
  EXPECT_EQ(asset->mesh.faces.size(), 50000u);
  ASSERT_EQ(asset->color.values.size(), 25002u);
  // Greyscale (R = G = B), opaque.
  for (const Eigen::Vector4f& c : asset->color.values) {
    ASSERT_EQ(c.x(), c.y());
    ASSERT_EQ(c.y(), c.z());
    ASSERT_EQ(c.w(), 1.0f);
  }
  EXPECT_TRUE(asset->uv.empty());
  EXPECT_TRUE(AnyNote(*asset, "vertex normals (nx, ny, nz) not carried"));
  const auto mesh = ReadMesh(path);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(asset->mesh.positions, mesh->positions);
}

}  // namespace
}  // namespace meshwave
