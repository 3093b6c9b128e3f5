// meshwave info FILE [--json]: what a mesh file holds.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_util.h"
#include "commands.h"
#include "meshwave.pb.h"
#include "meshwave/container.h"
#include "meshwave/gltf.h"
#include "meshwave/progression.h"
#include "meshwave/texture.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/semiregular.h"
#include "meshwave/stream_limits.h"
#include "meshwave/subdivision.h"

namespace meshwave::cli {
namespace {

struct InfoArgs {
  std::string file;
  bool json = false;
  int max_levels = kMaxStreamLevels;
};

void FillTopology(const MeshStats& s, proto::Topology& t) {
  t.set_vertices(s.vertices);
  t.set_unreferenced_vertices(s.unreferenced_vertices);
  t.set_faces(s.faces);
  t.set_edges(s.edges);
  t.set_boundary_edges(s.boundary_edges);
  t.set_boundary_loops(s.boundary_loops);
  t.set_components(s.components);
  t.set_manifold(s.manifold);
  t.set_closed(s.closed);
  t.set_non_manifold_edges(s.non_manifold_edges);
  t.set_non_manifold_vertices(s.non_manifold_vertices);
  t.set_inconsistently_oriented_edges(s.inconsistently_oriented_edges);
  t.set_euler_characteristic(s.euler_characteristic);
  if (s.manifold && s.genus >= 0) t.set_genus(s.genus);
}

// The file's attributes (UVs, colours, materials, images), read apart from
// the geometry: a texture that cannot be read leaves the rest of the
// description intact.
void FillAsset(const std::string& file, proto::AssetInfo& out) {
  const Result<MeshAsset> asset = ReadMeshAsset(file);
  if (!asset.ok()) {
    out.set_error(asset.status().ToString());
    return;
  }
  out.set_uv_values(asset->uv.values.size());
  out.set_color_values(asset->color.values.size());
  for (const Material& m : asset->materials) out.add_materials(m.name);
  for (const AssetImage& image : asset->images) {
    proto::AssetInfo::Image& i = *out.add_images();
    i.set_name(image.name);
    i.set_mime_type(image.mime_type);
    i.set_width(image.rgba.empty() ? 0 : image.width);
    i.set_height(image.rgba.empty() ? 0 : image.height);
  }
  for (const std::string& note : asset->notes) out.add_notes(note);
  out.set_summary(DescribeMeshAsset(*asset));
}

const char* FormatName(MeshFormat format, const std::string& file) {
  switch (format) {
    case MeshFormat::kPly:
      return "ply";
    case MeshFormat::kObj:
      return "obj";
    case MeshFormat::kOff:
      return "off";
    case MeshFormat::kGltf:
      return GltfFormFromPath(file) == GltfForm::kBinary ? "glb" : "gltf";
  }
  return "?";
}

Result<proto::MeshInfo> Describe(const InfoArgs& args) {
  MW_ASSIGN_OR_RETURN(MeshFormat format, FormatFromPath(args.file));
  MW_ASSIGN_OR_RETURN(TriMesh mesh, ReadMesh(args.file));
  proto::MeshInfo info;
  info.set_file(args.file);
  info.set_format(FormatName(format, args.file));
  FillAsset(args.file, *info.mutable_asset());
  info.set_file_vertices(mesh.positions.size());
  info.set_file_faces(mesh.faces.size());
  FillTopology(ComputeStats(mesh), *info.mutable_as_read());
  const Aabb box = BoundingBox(mesh.positions);
  for (int i = 0; i < 3; ++i) {
    info.mutable_bbox()->add_min(box.min[i]);
    info.mutable_bbox()->add_max(box.max[i]);
  }
  info.mutable_bbox()->set_diagonal(box.Diagonal());

  const CleanReport clean = CleanMesh(mesh);
  proto::Cleaning& c = *info.mutable_cleaning();
  c.set_merged_vertices(clean.merged_vertices);
  c.set_degenerate_faces(clean.degenerate_faces);
  c.set_duplicate_faces(clean.duplicate_faces);
  c.set_unreferenced_vertices(clean.unreferenced_vertices);
  c.set_zero_area_faces(clean.zero_area_faces);
  FillTopology(ComputeStats(mesh), *info.mutable_cleaned());

  DetectOptions options;
  options.max_levels = args.max_levels;
  auto detected = DetectSemiRegular(mesh, options);
  if (detected.ok()) {
    const auto& h = *detected->mesh.hierarchy;
    info.set_semiregular_levels(h.levels());
    info.set_base_vertices(h.vertex_count(0));
    info.set_base_faces(h.faces(0).size());
    info.set_semiregular_note("stopped: " + detected->stop_reason);
  } else {
    info.set_semiregular_levels(0);
    info.set_semiregular_note(detected.status().message());
  }
  return info;
}

// One row of the as-read / cleaned table; the cleaned column is left empty
// when cleaning changed nothing there.
void Row(const char* key, const std::string& as_read, const std::string& cleaned) {
  if (cleaned == as_read) {
    std::printf("%-23s %s\n", key, as_read.c_str());
  } else {
    std::printf("%-23s %-16s %s\n", key, as_read.c_str(), cleaned.c_str());
  }
}

void PrintTopology(const proto::Topology& a, const proto::Topology& b) {
  auto num = [](uint64_t v) { return std::to_string(v); };
  auto manifold = [&](const proto::Topology& t) {
    if (t.manifold()) return std::string("yes");
    return "no (" + num(t.non_manifold_edges()) + " edges, " +
           num(t.non_manifold_vertices()) + " vertices)";
  };
  auto genus = [](const proto::Topology& t) {
    return t.has_genus() ? std::to_string(t.genus()) : std::string("n/a");
  };
  // One column when cleaning changed nothing.
  if (a.SerializeAsString() == b.SerializeAsString()) {
    Row("", "as read (cleaning changed nothing)", "as read (cleaning changed nothing)");
  } else {
    Row("", "as read", "cleaned");
  }
  Row("vertices:", num(a.vertices()), num(b.vertices()));
  Row("unreferenced vertices:", num(a.unreferenced_vertices()),
      num(b.unreferenced_vertices()));
  Row("faces:", num(a.faces()), num(b.faces()));
  Row("edges:", num(a.edges()), num(b.edges()));
  Row("boundary edges:", num(a.boundary_edges()), num(b.boundary_edges()));
  Row("boundary loops:", num(a.boundary_loops()), num(b.boundary_loops()));
  Row("components:", num(a.components()), num(b.components()));
  Row("manifold:", manifold(a), manifold(b));
  Row("closed:", a.closed() ? "yes" : "no", b.closed() ? "yes" : "no");
  Row("misoriented edges:", num(a.inconsistently_oriented_edges()),
      num(b.inconsistently_oriented_edges()));
  Row("euler characteristic:", std::to_string(a.euler_characteristic()),
      std::to_string(b.euler_characteristic()));
  Row("genus:", genus(a), genus(b));
}

void PrintHuman(const proto::MeshInfo& i) {
  auto line = [](const char* key, const std::string& value) {
    std::printf("%-23s %s\n", key, value.c_str());
  };
  auto num = [](uint64_t v) { return std::to_string(v); };
  line("file:", i.file() + " (" + i.format() + ", " + num(i.file_vertices()) +
                    " vertex records, " + num(i.file_faces()) + " triangles)");
  PrintTopology(i.as_read(), i.cleaned());
  char box[256];
  std::snprintf(box, sizeof box, "[%.6g %.6g %.6g] - [%.6g %.6g %.6g]",
                i.bbox().min(0), i.bbox().min(1), i.bbox().min(2),
                i.bbox().max(0), i.bbox().max(1), i.bbox().max(2));
  line("bounding box:", box);
  std::snprintf(box, sizeof box, "%.6g", i.bbox().diagonal());
  line("diagonal:", box);
  const proto::Cleaning& c = i.cleaning();
  line("cleaning:", num(c.merged_vertices()) + " duplicate vertices merged, " +
                        num(c.degenerate_faces()) + " degenerate and " +
                        num(c.duplicate_faces()) + " duplicate faces dropped, " +
                        num(c.unreferenced_vertices()) +
                        " unreferenced vertices dropped, " +
                        num(c.zero_area_faces()) + " zero-area faces kept");
  if (i.semiregular_levels() > 0) {
    line("semi-regular levels:",
         num(i.semiregular_levels()) + " (base " + num(i.base_vertices()) +
             " vertices, " + num(i.base_faces()) + " faces)");
  } else {
    line("semi-regular levels:", "0 (" + i.semiregular_note() + ")");
  }
  line("attributes:", i.asset().error().empty()
                          ? i.asset().summary()
                          : "not readable: " + i.asset().error());
}

// The texture's atlas and maps, each level's bytes and whether it is held.
template <typename Line, typename Num>
void DescribeTexture(const StreamHeader& h, const ParsedContainer& parsed, const Line& line,
                     const Num& num) {
  if (!h.texture) return;
  const StreamHeader::Texture& t = *h.texture;
  line("texture atlas:", num(t.columns) + " columns of " + num(t.cell) + "-texel cells, gutter " +
                             num(t.gutter));
  std::vector<char> present(h.packets.length.size(), 0);
  for (uint32_t id : parsed.ids) present[id] = 1;
  for (const StreamHeader::Texture::Map& map : t.maps) {
    std::string levels;
    for (const StreamHeader::Texture::Level& level : map.levels) {
      levels += (levels.empty() ? "" : ", ") + num(level.width) + " x " + num(level.height) +
                " (" + num(h.packets.length[level.packet]) + " bytes" +
                (present[level.packet] ? "" : ", not held") + ")";
    }
    line("texture map:", std::string(TextureRoleName(static_cast<TextureRole>(map.role))) + ", " +
                             map.mime_type + ", " + num(map.levels.size()) +
                             (map.levels.size() == 1 ? " level: " : " levels: ") + levels);
  }
}

// A stream (.mwv): its header's counts, channels and texture, and the
// packets the file holds.
Status DescribeStream(const InfoArgs& args) {
  if (args.json) return InvalidArgument("--json describes mesh files, not .mwv streams");
  MW_ASSIGN_OR_RETURN(std::string bytes, ReadFileBytes(args.file));
  auto parsed = ParseContainer(bytes, /*allow_truncated=*/true);
  if (!parsed.ok()) return parsed.status().WithContext(args.file);
  const StreamHeader& h = parsed->header;
  MW_RETURN_IF_ERROR(ValidateStreamHeader(h).WithContext(args.file));
  auto line = [](const char* key, const std::string& value) {
    std::printf("%-23s %s\n", key, value.c_str());
  };
  auto num = [](uint64_t v) { return std::to_string(v); };
  line("file:", args.file + " (meshwave stream, format version " + num(h.format_version) +
                    (parsed->missing_bytes > 0
                         ? ", cut short: " + num(parsed->missing_bytes) + " bytes missing"
                         : std::string()) +
                    ")");
  if (!h.name.empty()) line("name:", h.name);
  line("mesh:", num(h.vertices) + " vertices, " + num(h.faces) + " faces, " +
                    num(h.transform.levels) + " levels over a base of " +
                    num(h.base.vertex_count) + " vertices, " + num(h.base.face_count) +
                    " faces");
  uint64_t held = 0;
  for (std::string_view payload : parsed->payloads) held += payload.size();
  line("packets:", num(parsed->ids.size()) + " of " + num(h.packets.length.size()) +
                       " held (" + num(held) + " payload bytes)");
  for (const StreamHeader::Channel& channel : h.channels) {
    line("channel:", channel.kind == StreamChannelKind::kColor ? "vertex colours" : "unknown");
  }
  if (h.original) {
    // The last packets of the index (docs/FORMAT.md 2.5).
    const size_t parts = OriginalPackets(h);
    const size_t first = h.packets.length.size() - parts;
    uint64_t layer_bytes = 0;
    size_t held_parts = 0;
    for (size_t id = first; id < h.packets.length.size(); ++id) layer_bytes += h.packets.length[id];
    for (uint32_t id : parsed->ids) held_parts += id >= first ? 1 : 0;
    line("original layer:", num(h.original->vertex_count) + " vertices, " +
                                num(h.original->face_count) + " faces, " + num(parts) +
                                " packets of " + num(layer_bytes) + " bytes (" + num(held_parts) +
                                " held)");
  }
  DescribeTexture(h, *parsed, line, num);
  return Status::Ok();
}


}  // namespace

void AddInfoCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Describe a mesh file: counts, topology, bounding box, "
              "semi-regular levels, and its UVs, colours, materials and "
              "images; or a stream (.mwv): its counts, packets and texture maps");
  cmd->add_option("file", args->file,
                  "Mesh file (.ply, .obj, .off, .glb, .gltf) or stream (.mwv)")
      ->required();
  cmd->add_flag("--json", args->json, "Print JSON instead of text");
  cmd->add_option("--max-levels", args->max_levels,
                  "Stop looking for subdivision levels after this many")
      ->check(CLI::Range(0, kMaxStreamLevels));
  cmd->callback([args, &exit_code] {
    if (std::filesystem::path(args->file).extension() == ".mwv") {
      if (const Status s = DescribeStream(*args); !s.ok()) exit_code = Fail("info", s);
      return;
    }
    auto info = Describe(*args);
    if (!info.ok()) {
      exit_code = Fail("info", info.status());
      return;
    }
    if (args->json) {
      PrintJson(*info);
    } else {
      PrintHuman(*info);
    }
  });
}

}  // namespace meshwave::cli
