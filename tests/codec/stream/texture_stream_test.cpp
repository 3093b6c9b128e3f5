// Textures in the stream (format version 9): the header field read back by
// both readers, refused with a message when it does not fit; texture
// packets placed in every order without moving the geometry's; every
// corner's UV from the atlas; the finest level held of each map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "codec/stream/stream_header_compare_testonly.h"
#include "codec/stream/stream_test_util.h"
#include "codec/texture/png_testonly.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/region.h"
#include "meshwave/region_order.h"
#include "stream.pb.h"
#include "stream/packet_index.h"
#include "test_data.h"
#include "texture/atlas_layout.h"

namespace meshwave {
namespace texture_stream_test {
namespace {

// A cube of 12 faces: 6 cells of 64 texels in 3 columns make a 192 x 128
// atlas, die.png's size.
TriMesh Cube() {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
             {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

const SemiRegularMesh& Mesh() {
  static const SemiRegularMesh mesh = [] {
    auto sr = Subdivide(Cube(), 2, SubdivisionScheme::kButterfly);
    EXPECT_TRUE(sr.ok()) << sr.status().ToString();
    for (Vec3& p : sr->positions) p += 0.05 * Vec3(std::sin(7 * p.y()), 0, std::cos(5 * p.x()));
    return *std::move(sr);
  }();
  return mesh;
}

std::string DiePng() {
  std::ifstream in(testing::SampleMesh("textured/die.png"), std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A base colour map of three levels (two generated, the finest die.png)
// and a normal map of one (die.png): sizes consistent with the atlas.
BakedTexture TestTexture() {
  BakedTexture t;
  t.atlas = {64, 2, 3};
  t.material.emissive_factor = {0.1f, 0.2f, 0.3f};
  t.material.double_sided = true;
  t.maps.push_back({TextureRole::kBaseColor, "image/png",
                    {testing::SolidPng(48, 32, 200, 40, 40),
                     testing::SolidPng(96, 64, 40, 200, 40), DiePng()}});
  t.maps.push_back({TextureRole::kNormal, "image/png", {DiePng()}});
  return t;
}

const EncodedStream& Plain() {
  static const EncodedStream stream = [] {
    auto s = EncodeMesh(Mesh(), EncodeOptions{});
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    return *std::move(s);
  }();
  return stream;
}

const EncodedStream& Textured() {
  static const EncodedStream stream = [] {
    VertexAttributes attributes;
    attributes.texture = TestTexture();
    auto s = EncodeMesh(Mesh(), EncodeOptions{}, attributes);
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    return *std::move(s);
  }();
  return stream;
}

std::vector<uint32_t> TextureIds(const StreamHeader& h) {
  std::vector<uint32_t> ids;
  for (const auto& map : h.texture->maps) {
    for (const auto& level : map.levels) ids.push_back(level.packet);
  }
  return ids;
}

TEST(TextureStreamTest, HeaderCarriesTheTextureAndBothReadersAgree) {
  const EncodedStream& s = Textured();
  EXPECT_EQ(s.header.format_version, kStreamFormatVersion);
  ASSERT_TRUE(s.header.texture.has_value());
  const StreamHeader::Texture& t = *s.header.texture;
  EXPECT_EQ(t.cell, 64u);
  EXPECT_EQ(t.gutter, 2u);
  EXPECT_EQ(t.columns, 3u);
  ASSERT_EQ(t.maps.size(), 2u);
  ASSERT_EQ(t.maps[0].levels.size(), 3u);
  EXPECT_EQ(t.maps[0].levels[0].width, 48u);
  EXPECT_EQ(t.maps[0].levels[1].height, 64u);
  EXPECT_EQ(t.maps[0].levels[2].width, 192u);
  EXPECT_EQ(t.maps[1].role, static_cast<int32_t>(TextureRole::kNormal));
  // The texture packets follow the geometry's, whose bytes are the plain
  // stream's: a texture changes nothing of the geometry.
  const std::vector<uint32_t> ids = TextureIds(s.header);
  ASSERT_EQ(s.packets.size(), Plain().packets.size() + 4);
  for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(ids[i], Plain().packets.size() + i);
  for (size_t i = 0; i < Plain().packets.size(); ++i) EXPECT_EQ(s.packets[i], Plain().packets[i]);
  EXPECT_EQ(s.packets[ids[3]], DiePng());
  proto::StreamHeader p;
  ASSERT_TRUE(p.ParseFromString(s.header.bytes_without_present));
  EXPECT_EQ(testing::HeaderDifference(s.header, p), "");
  // The decoder's description.
  auto d = testing::DecoderOf(s);
  ASSERT_TRUE(d->HasTexture());
  const TextureInfo& info = d->texture();
  EXPECT_EQ(info.atlas.columns, 3u);
  EXPECT_FLOAT_EQ(info.material.emissive_factor[2], 0.3f);
  EXPECT_TRUE(info.material.double_sided);
  EXPECT_FLOAT_EQ(info.material.metallic_factor, 1.0f);
  ASSERT_EQ(info.maps.size(), 2u);
  EXPECT_EQ(info.maps[0].mime_type, "image/png");
  EXPECT_EQ(info.maps[0].levels[0].width, 48u);
  EXPECT_FALSE(testing::DecoderOf(Plain())->HasTexture());
  EXPECT_TRUE(testing::DecoderOf(Plain())->TextureCoordinates().empty());
}

// The textured header with one change, read back and validated.
Status Validated(const std::function<void(proto::StreamHeader&)>& change) {
  proto::StreamHeader p;
  EXPECT_TRUE(p.ParseFromString(Textured().header.bytes_without_present));
  change(p);
  auto read = ReadStreamHeader(p.SerializeAsString());
  if (!read.ok()) return read.status();
  return ValidateStreamHeader(*read);
}

TEST(TextureStreamTest, RefusesTextureFieldsThatDoNotFit) {
  EXPECT_TRUE(Validated([](proto::StreamHeader&) {}).ok());
  struct Case {
    const char* what;
    std::function<void(proto::StreamHeader&)> change;
  };
  const std::vector<Case> cases = {
      {"with a texture (textures came with version 9)",
       [](proto::StreamHeader& p) { p.set_format_version(8); }},
      {"image type \"image/gif\" (image/jpeg, image/png or image/webp)",
       [](proto::StreamHeader& p) { p.mutable_texture()->mutable_maps(0)->set_mime_type("image/gif"); }},
      {"with a WebP texture (WebP came with version 11)",
       [](proto::StreamHeader& p) {
         p.set_format_version(10);
         p.mutable_texture()->mutable_maps(0)->set_mime_type("image/webp");
       }},
      {"level 1 is 96 x 65, not 96 x 64 (the atlas's size / 2^1)",
       [](proto::StreamHeader& p) {
         p.mutable_texture()->mutable_maps(0)->mutable_levels(1)->set_height(65);
       }},
      {"level 0 names packet 3, not",
       [](proto::StreamHeader& p) {
         p.mutable_texture()->mutable_maps(0)->mutable_levels(0)->set_packet(3);
       }},
      {"a second map of its role",
       [](proto::StreamHeader& p) { p.mutable_texture()->mutable_maps(1)->set_role(proto::TEXTURE_BASE_COLOR); }},
      {"unknown role 7",
       [](proto::StreamHeader& p) {
         p.mutable_texture()->mutable_maps(1)->set_role(static_cast<proto::TextureRole>(7));
       }},
      {"9 levels (1 to 8)",
       [](proto::StreamHeader& p) {
         auto* map = p.mutable_texture()->mutable_maps(1);
         for (int k = 0; k < 8; ++k) *map->add_levels() = map->levels(0);
       }},
      {"cell of 48 texels",
       [](proto::StreamHeader& p) { p.mutable_texture()->set_cell(48); }},
      {"the atlas has 0 columns",
       [](proto::StreamHeader& p) { p.mutable_texture()->set_columns(0); }},
      {"7 face triangles for 12 base faces",
       [](proto::StreamHeader& p) {
         p.mutable_texture()->clear_face_triangles();
         for (uint32_t f = 0; f < 7; ++f) p.mutable_texture()->add_face_triangles(3 * f);
       }},
      {"names triangle 0 (named twice)",
       [](proto::StreamHeader& p) {
         p.mutable_texture()->clear_face_triangles();
         for (uint32_t f = 0; f < 12; ++f) p.mutable_texture()->add_face_triangles(f == 11 ? 0 : 3 * f);
       }},
      {"rd weight not finite and positive",
       [](proto::StreamHeader& p) { p.mutable_texture()->set_rd_weight(0); }},
      {"0 maps (1 to 5)",
       [](proto::StreamHeader& p) { p.mutable_texture()->clear_maps(); }},
      {"a material scalar is not finite",
       [](proto::StreamHeader& p) { p.mutable_texture()->set_normal_scale(std::nanf("")); }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const Status s = Validated(c.change);
    EXPECT_EQ(s.code(), StatusCode::kParseError) << s.ToString();
    EXPECT_NE(s.message().find(c.what), std::string::npos) << s.message();
  }
}

TEST(TextureStreamTest, EncoderRefusesATextureThatDoesNotFitTheMesh) {
  struct Case {
    const char* what;
    std::function<void(BakedTexture&)> change;
  };
  const std::vector<Case> cases = {
      {"level 0 is 48 x 32 pixels, not 96 x 16",
       [](BakedTexture& t) { t.atlas.columns = 6; }},
      {"image type \"image/gif\"", [](BakedTexture& t) { t.maps[1].mime_type = "image/gif"; }},
      {"not a JPEG", [](BakedTexture& t) { t.maps[1].mime_type = "image/jpeg"; }},
      {"not a WebP", [](BakedTexture& t) { t.maps[1].mime_type = "image/webp"; }},
      {"a second map of its role", [](BakedTexture& t) { t.maps[1].role = TextureRole::kBaseColor; }},
      {"0 levels (1 to 8)", [](BakedTexture& t) { t.maps[1].levels.clear(); }},
      {"0 maps", [](BakedTexture& t) { t.maps.clear(); }},
      {"cell of 12 texels", [](BakedTexture& t) { t.atlas.cell = 12; }},
      {"not finite", [](BakedTexture& t) { t.material.roughness_factor = INFINITY; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    VertexAttributes attributes;
    attributes.texture = TestTexture();
    c.change(*attributes.texture);
    auto s = EncodeMesh(Mesh(), EncodeOptions{}, attributes);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(s.status().message().find(c.what), std::string::npos) << s.status().message();
  }
}

std::vector<uint32_t> Without(const std::vector<uint32_t>& order, size_t first_texture) {
  std::vector<uint32_t> out;
  for (uint32_t id : order) {
    if (id < first_texture) out.push_back(id);
  }
  return out;
}

size_t Position(const std::vector<uint32_t>& order, uint32_t id) {
  return static_cast<size_t>(std::find(order.begin(), order.end(), id) - order.begin());
}

TEST(TextureStreamTest, OrdersPlaceTextureLevelsAndKeepTheGeometrysOrder) {
  const StreamHeader& h = Textured().header;
  const size_t first = Plain().packets.size();
  const std::vector<uint32_t> ids = TextureIds(h);
  const PacketLayout layout(h);
  const int levels = layout.levels();  // 2
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    SCOPED_TRACE(ProgressionName(p));
    const auto order = PacketOrder(h, p);
    ASSERT_EQ(order.size(), h.packets.length.size());
    // The other packets keep their order (so do their bytes, above).
    EXPECT_EQ(Without(order, first), PacketOrder(Plain().header, p));
    // A map's levels coarsest first, and every prefix decodes.
    EXPECT_LT(Position(order, ids[0]), Position(order, ids[1]));
    EXPECT_LT(Position(order, ids[1]), Position(order, ids[2]));
    auto d = testing::DecoderOf(Textured());
    for (uint32_t id : order) ASSERT_TRUE(d->AddPacket(id, Textured().packets[id]).ok()) << id;
  }
  // Resolution: level k of 3 matches mesh level max(0, 2 - (2 - k)) = k:
  // after the packets of subband k - 1 and before subband k's.
  const auto resolution = PacketOrder(h, Progression::kResolution);
  for (int k = 0; k < 3; ++k) {
    const size_t at = Position(resolution, ids[static_cast<size_t>(k)]);
    for (size_t i = 0; i < resolution.size(); ++i) {
      const uint32_t id = resolution[i];
      if (layout.IsTexture(id) || layout.IsBase(id)) continue;
      if (layout.Subband(id) < k) {
        EXPECT_LT(i, at) << "level " << k << ", packet " << id;
      } else {
        EXPECT_GT(i, at) << "level " << k << ", packet " << id;
      }
    }
  }
  // The normal map's one level is full size: mesh level 2, after all.
  EXPECT_GT(Position(resolution, ids[3]), Position(resolution, ids[1]));
  // max_level 1 keeps the levels matching mesh levels 0 and 1 only.
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    const auto order = PacketOrder(h, p, levels - 1);
    EXPECT_NE(Position(order, ids[1]), order.size());
    EXPECT_EQ(Position(order, ids[2]), order.size());
    EXPECT_EQ(Position(order, ids[3]), order.size());
  }
  // Quality: a texture level goes before the first packet from which on
  // nothing is worth more per byte (the rd order's values).
  const auto quality = PacketOrder(h, Progression::kQuality);
  const DistortionEstimates e = ReadDistortionIndex(h, PacketChains(h));
  const double d2 = HeaderDiagonal(h) * HeaderDiagonal(h);
  auto value = [&](uint32_t id) {
    const double scale = layout.IsTexture(id) ? h.texture->rd_weight * d2 : 1.0;
    return e.reduction[id] * scale / (h.packets.length[id] + 4.0);
  };
  for (uint32_t id : ids) {
    const size_t at = Position(quality, id);
    double rest = 0;
    for (size_t i = at; i < quality.size(); ++i) {
      if (!layout.IsTexture(quality[i])) rest = std::max(rest, value(quality[i]));
    }
    EXPECT_GE(value(id), rest) << "texture packet " << id;
    if (at > 0 && !layout.IsTexture(quality[at - 1])) {
      // Not placeable earlier: the packet before it opened a run worth more.
      double before = 0;
      for (size_t i = at - 1; i < quality.size(); ++i) {
        if (!layout.IsTexture(quality[i])) before = std::max(before, value(quality[i]));
      }
      EXPECT_LT(value(id), before) << "texture packet " << id;
    }
  }
}

TEST(TextureStreamTest, RegionOrderSendsTextureLevelsOnceCoarsestFirst) {
  const EncodedStream& s = Textured();
  auto precincts = StreamPrecincts::Create(s.header);
  ASSERT_TRUE(precincts.ok()) << precincts.status().ToString();
  auto d = testing::DecoderOf(s);
  std::vector<std::vector<uint32_t>> parts(s.packets.size());
  for (uint32_t id = 0; id < s.packets.size(); ++id) {
    auto lengths = PartLengths(d->held(), id, s.packets[id]);
    ASSERT_TRUE(lengths.ok());
    parts[id] = *lengths;
  }
  Region region;
  region.shape = SphereRegion{Vec3(0.5, 0.5, 0.0), 0.3};
  const auto units = RegionOrder(s.header, *precincts, parts, region, d->held());
  std::vector<uint32_t> textures;
  for (const StreamUnit& u : units) {
    if (u.id >= Plain().packets.size()) textures.push_back(u.id);
  }
  std::vector<uint32_t> ids = TextureIds(s.header);
  std::vector<uint32_t> sorted = textures;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, ids);
  EXPECT_LT(Position(textures, ids[0]), Position(textures, ids[1]));
  EXPECT_LT(Position(textures, ids[1]), Position(textures, ids[2]));
}

// Barycentric coordinates of face F's corners of level j in its base face,
// by the children rule of meshwave/semiregular.h, digit by digit.
std::array<Eigen::Vector3d, 3> CornerBarycentrics(uint64_t face, int level) {
  std::array<Eigen::Vector3d, 3> p = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                      Eigen::Vector3d(0, 0, 1)};
  for (int depth = level - 1; depth >= 0; --depth) {
    const int child = static_cast<int>((face >> (2 * depth)) & 3);
    const Eigen::Vector3d ab = (p[0] + p[1]) / 2, bc = (p[1] + p[2]) / 2, ca = (p[2] + p[0]) / 2;
    switch (child) {
      case 0: p = {p[0], ab, ca}; break;
      case 1: p = {p[1], bc, ab}; break;
      case 2: p = {p[2], ca, bc}; break;
      default: p = {ab, bc, ca}; break;
    }
  }
  return p;
}

TEST(TextureStreamTest, CornerCoordinatesComeFromTheAtlas) {
  const EncodedStream& s = Textured();
  const StreamHeader::Texture& t = *s.header.texture;
  auto atlas = AtlasLayout::Create(s.header.base.face_count, t.cell, t.gutter, t.columns);
  ASSERT_TRUE(atlas.ok());
  auto d = testing::DecoderOf(s);
  const int levels = static_cast<int>(s.header.transform.levels);
  // Per (base face, vertex): its UV, which every level must agree on.
  std::map<std::pair<uint64_t, uint32_t>, std::pair<float, float>> seen;
  for (int j = 0; j <= levels; ++j) {
    SCOPED_TRACE("level " + std::to_string(j));
    const std::vector<Face> faces = d->Faces(j);
    const std::vector<float> uv = d->TextureCoordinates(j);
    ASSERT_EQ(uv.size(), 6 * faces.size());
    for (uint64_t f = 0; f < faces.size(); ++f) {
      const uint64_t base = f >> (2 * j);
      uint32_t triangle = static_cast<uint32_t>(base), r = 0;
      if (!t.face_triangles.empty()) {
        triangle = t.face_triangles[base] / 3;
        r = t.face_triangles[base] % 3;
      }
      const auto bary = CornerBarycentrics(f, j);
      for (int i = 0; i < 3; ++i) {
        // Corner i of the stream's face is corner (i + r) mod 3 of the
        // triangle: barycentrics permuted accordingly.
        double b[3];
        for (int c = 0; c < 3; ++c) b[(c + r) % 3] = bary[static_cast<size_t>(i)][c];
        const AtlasPoint q = atlas->Map(triangle, b[0], b[1], b[2]);
        const float u = uv[6 * f + 2 * static_cast<size_t>(i)];
        const float v = uv[6 * f + 2 * static_cast<size_t>(i) + 1];
        EXPECT_NEAR(u, q.x / atlas->width(), 1e-6);
        EXPECT_NEAR(v, q.y / atlas->height(), 1e-6);
        const auto key = std::make_pair(base, faces[f][static_cast<size_t>(i)]);
        const auto [it, fresh] = seen.emplace(key, std::make_pair(u, v));
        if (!fresh) {
          EXPECT_EQ(it->second.first, u);
          EXPECT_EQ(it->second.second, v);
        }
      }
    }
  }
  // The stream reordered the base: its faces name their triangles.
  EXPECT_EQ(t.face_triangles.size(), 12u);
}

TEST(TextureStreamTest, BestLevelIsTheFinestHeld) {
  const EncodedStream& s = Textured();
  const std::vector<uint32_t> ids = TextureIds(s.header);
  auto d = testing::DecoderOf(s);
  EXPECT_FALSE(d->BestTextureLevel(0).has_value());
  EXPECT_FALSE(d->BestTextureLevel(2).has_value());  // no such map
  ASSERT_TRUE(d->AddPacket(ids[1], s.packets[ids[1]]).ok());  // needs nothing
  auto best = d->BestTextureLevel(0);
  ASSERT_TRUE(best.has_value());
  EXPECT_EQ(best->level, 1);
  EXPECT_EQ(best->width, 96u);
  EXPECT_EQ(best->height, 64u);
  EXPECT_EQ(best->mime_type, "image/png");
  EXPECT_EQ(best->bytes, s.packets[ids[1]]);
  ASSERT_TRUE(d->AddPacket(ids[0], s.packets[ids[0]]).ok());
  EXPECT_EQ(d->BestTextureLevel(0)->level, 1);  // a coarser one changes nothing
  EXPECT_FALSE(d->BestTextureLevel(1).has_value());
  // A damaged image is refused by the index's check.
  std::string damaged = s.packets[ids[2]];
  damaged[damaged.size() / 2] ^= 0x20;
  EXPECT_EQ(d->AddPacket(ids[2], damaged).code(), StatusCode::kParseError);
  ASSERT_TRUE(d->AddPacket(ids[2], s.packets[ids[2]]).ok());
  EXPECT_EQ(d->BestTextureLevel(0)->level, 2);
  EXPECT_EQ(d->BestTextureLevel(0)->bytes, DiePng());
  // Texture packets leave the geometry's estimate alone.
  EXPECT_EQ(d->EstimatedPsnr(), testing::DecoderOf(s)->EstimatedPsnr());
  d->Reset();
  EXPECT_FALSE(d->BestTextureLevel(0).has_value());
  // Through a container prefix: what a client holds.
  const std::string prefix = SerializeContainer(s, std::vector<uint32_t>{ids[3]});
  auto parsed = ParseContainer(prefix);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  auto e = testing::DecoderOf(s);
  ASSERT_TRUE(e->AddPacket(parsed->ids[0], parsed->payloads[0]).ok());
  EXPECT_EQ(e->BestTextureLevel(1)->role, TextureRole::kNormal);
}

// Writes the textured stream where MESHWAVE_TEXTURED_STREAM_OUT says (the
// glTF validator's test decodes it with the CLI); without it, checks that
// the container reads back.
TEST(TextureStreamTest, WritesATexturedContainer) {
  const std::string bytes = SerializeFullContainer(Textured());
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  ASSERT_TRUE(parsed->header.texture.has_value());
  if (const char* out = std::getenv("MESHWAVE_TEXTURED_STREAM_OUT")) {
    std::ofstream file(out, std::ios::binary);
    file << bytes;
    ASSERT_TRUE(file.good()) << out;
  }
}

}  // namespace
}  // namespace texture_stream_test
}  // namespace meshwave
