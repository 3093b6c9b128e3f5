// The asset pipeline (meshwave/asset_encoder.h) that `meshwave encode` and
// the server's ingest share: colours carried from a coloured PLY, the same
// container as the geometry-only path for a mesh without attributes, the
// geometry alone (and said so) when the asset's sidecar files are missing.
#include "meshwave/asset_encoder.h"

#include <gtest/gtest.h>

#include "meshwave/container.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_io.h"
#include "test_data.h"

namespace meshwave {
namespace {

AssetEncodeOptions Options(const std::string& name) {
  AssetEncodeOptions options;
  options.encode.name = name;
  options.semiregular.fidelity_db = 0;  // one remesh: fast
  return options;
}

TEST(AssetEncoderTest, CarriesTheColoursOfAColouredPly) {
  DirectoryFileSet files(testing::SampleMesh("textured"));
  AssetEncodeOptions options = Options("hue_ball");
  int reports = 0;
  options.on_read = [&](const AssetRead& read) {
    EXPECT_TRUE(read.attributes_read);
    EXPECT_TRUE(read.colors);
    EXPECT_GT(read.faces, 0u);
    ++reports;
  };
  options.on_semiregular = [&](const SemiRegularInput& input) {
    EXPECT_GT(input.mesh.positions.size(), 0u);  // not yet released
    ++reports;
  };
  auto encoded = EncodeAsset(files, "hue_ball.ply", options);
  ASSERT_TRUE(encoded.ok()) << encoded.status().ToString();
  EXPECT_EQ(reports, 2);
  ASSERT_EQ(encoded->stream.header.channels.size(), 1u);
  EXPECT_EQ(encoded->stream.colors.size(), encoded->stream.mesh.positions.size());
  EXPECT_TRUE(encoded->input_mesh.positions.empty());  // not asked to keep it
  EXPECT_TRUE(encoded->semiregular.mesh.positions.empty());  // released after encoding
}

// A mesh without attributes: the container is byte for byte what reading,
// remeshing and encoding the geometry alone gives (as both callers did
// before the pipeline).
TEST(AssetEncoderTest, AMeshWithoutAttributesEncodesAsTheGeometryAlone) {
  for (const char* name : {"holes.off", "elephant.off"}) {
    AssetEncodeOptions options = Options(name);
    options.keep_input_mesh = true;
    DirectoryFileSet files(testing::SampleDataDir());
    auto encoded = EncodeAsset(files, name, options);
    ASSERT_TRUE(encoded.ok()) << encoded.status().ToString();
    EXPECT_TRUE(encoded->stream.header.channels.empty());
    EXPECT_TRUE(encoded->read.left_out.empty()) << encoded->read.left_out;

    auto mesh = ReadMesh(testing::SampleMesh(name));
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(encoded->input_mesh.positions, mesh->positions) << name;
    auto input = ToSemiRegular(std::move(*mesh), options.semiregular);
    ASSERT_TRUE(input.ok());
    EXPECT_EQ(encoded->semiregular.remeshed, input->remeshed);
    // The stream ends in the mesh as read (the original layer).
    VertexAttributes original;
    original.original = &encoded->input_mesh;
    if (encoded->semiregular.remeshed) {
      original.original_remesh_psnr_db = encoded->semiregular.remesh_psnr_db;
    }
    auto alone = EncodeMesh(input->mesh, options.encode, original);
    ASSERT_TRUE(alone.ok());
    ASSERT_TRUE(alone->header.original.has_value());
    EXPECT_EQ(SerializeFullContainer(encoded->stream), SerializeFullContainer(*alone)) << name;
  }
}

TEST(AssetEncoderTest, WithoutTheOriginalLayerTheStreamEndsInTheRemesh) {
  AssetEncodeOptions options = Options("holes.off");
  options.original_layer = false;
  DirectoryFileSet files(testing::SampleDataDir());
  auto encoded = EncodeAsset(files, "holes.off", options);
  ASSERT_TRUE(encoded.ok()) << encoded.status().ToString();
  EXPECT_FALSE(encoded->stream.header.original.has_value());
}

TEST(AssetEncoderTest, MissingSidecarFilesAreAnErrorThatOffersTheGeometry) {
  MemoryFileSet files;
  ASSERT_TRUE(files
                  .Add("tet.obj",
                       "mtllib tet.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\n"
                       "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n")
                  .ok());
  AssetEncodeOptions options = Options("tet");
  options.source_name = "uploads/tet.obj";
  bool read_reported = false;
  options.on_read = [&](const AssetRead&) { read_reported = true; };
  auto strict = EncodeAsset(files, "tet.obj", options);
  ASSERT_FALSE(strict.ok());
  EXPECT_EQ(strict.status().code(), StatusCode::kNotFound) << strict.status().ToString();
  EXPECT_NE(strict.status().message().find("tet.mtl"), std::string::npos)
      << strict.status().ToString();
  EXPECT_NE(strict.status().message().find("nothing encoded (its geometry alone reads: "
                                            "--allow-geometry-only"),
            std::string::npos)
      << strict.status().ToString();
  EXPECT_FALSE(read_reported);  // strict before any step began

  // Asked for: the geometry alone, and said so.
  options.geometry_if_attributes_unreadable = true;
  auto encoded = EncodeAsset(files, "tet.obj", options);
  ASSERT_TRUE(encoded.ok()) << encoded.status().ToString();
  EXPECT_FALSE(encoded->read.attributes_read);
  EXPECT_EQ(encoded->read.faces, 4u);
  EXPECT_EQ(encoded->read.left_out.rfind("uploads/tet.obj: the stream holds the geometry only", 0),
            0u)
      << encoded->read.left_out;
  EXPECT_NE(encoded->read.left_out.find("tet.mtl"), std::string::npos) << encoded->read.left_out;
  EXPECT_GT(encoded->stream.packets.size(), 0u);

  // Malformed geometry is still an error, naming the file as the user gave it.
  MemoryFileSet bad;
  ASSERT_TRUE(bad.Add("bad.off", "OFF\n3 1 0\n0 0 0\n").ok());
  options.source_name = "in/bad.off";
  auto refused = EncodeAsset(bad, "bad.off", options);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("in/bad.off"), std::string::npos)
      << refused.status().ToString();
}

TEST(AssetEncoderTest, TheLeftOutLineNamesWhatTheStreamDoesNotCarry) {
  MeshAsset asset;
  EXPECT_EQ(AttributesLeftOut("a.ply", asset), "");
  // UVs and a material but no texture: nothing to bake them into.
  asset.uv.faces = {{0, 0, 0}};
  asset.materials.resize(1);
  EXPECT_EQ(AttributesLeftOut("a.obj", asset),
            "a.obj: the stream holds the geometry; not coded: UVs (no texture uses them), "
            "1 material without a texture");
  // A texture: baked, with the colours; only the reader's notes are left.
  asset.materials.resize(2);
  asset.images.resize(1);
  EXPECT_EQ(AttributesLeftOut("a.glb", asset), "");
  asset.color.faces = {{0, 0, 0}};
  asset.notes = {"a.glb: 1 camera not carried"};
  EXPECT_EQ(AttributesLeftOut("a.glb", asset),
            "a.glb: the stream holds the geometry, vertex colours and the textures baked onto "
            "the remesh; not coded: 1 feature the reader leaves out (meshwave info lists them)");
}

}  // namespace
}  // namespace meshwave
