#include "ingest.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "core/durable_file.h"
#include "mesh_identity.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/asset_encoder.h"
#include "meshwave/container.h"
#include "meshwave/mesh_id.h"
#include "meshwave/encoder.h"
#include "meshwave/fidelity.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_io.h"
#include "meshwave/progression.h"
#include "meshwave/semiregular_input.h"
#include "recording_file_set.h"
#include "sha256.h"

namespace meshwave::server {
namespace {

const OriginalPart* FindPart(const std::vector<OriginalPart>& parts, const std::string& name) {
  for (const OriginalPart& p : parts) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

// Whether a mesh file of this name may refer to other files.
bool HasSidecarFiles(std::string_view name) {
  const std::string ext = std::filesystem::path(name).extension().string();
  std::string lower;
  for (char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == ".gltf" || lower == ".obj";
}

// Writes the original's files and the container, then inserts the row,
// all under the ingest lock. `e` is complete but for created_unix.
Result<IngestResult> Store(Catalog& catalog, CatalogEntry e, const std::string& container,
                           const Original* original, const std::vector<OriginalPart>& parts) {
  e.created_unix = NowUnix();
  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  MW_ASSIGN_OR_RETURN(auto existing, catalog.Find(e.id));
  if (existing) return IngestResult{*existing, true};
  if (original) MW_RETURN_IF_ERROR(WriteOriginal(catalog.store_dir(), *original, parts));
  MW_RETURN_IF_ERROR(WriteFileDurably(catalog.ContainerPath(e), container));
  if (Status s = catalog.Insert(e, original); !s.ok()) {
    // No row names the container (under the ingest lock, nobody else wrote
    // it): remove it, or a full disk would keep the space and leave an
    // orphan (found by FaultTest.DiskFullDuringIngest...). The original's
    // blobs may be another original's too: RemoveOrphans sorts them out.
    std::error_code ec;
    std::filesystem::remove(catalog.ContainerPath(e), ec);
    return s;
  }
  return IngestResult{e, false};
}

}  // namespace

int64_t NowUnix() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

CatalogEntry EntryFor(const EncodedMesh& encoded) {
  CatalogEntry e;
  e.sha256 = Sha256Hex(encoded.container);
  e.id = MeshIdFromSha256(e.sha256);
  e.vertices = encoded.header.vertices;
  e.faces = encoded.header.faces;
  e.levels = encoded.header.transform.levels;
  e.packets = static_cast<uint32_t>(encoded.packets);
  e.bytes = encoded.container.size();
  e.container = "containers/" + e.sha256 + ".mwv";
  e.format_version = encoded.header.format_version;
  return e;
}

namespace {

// Seconds since `start`, for the log of a long ingest.
double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Result<EncodedMesh> EncodeOriginal(const std::vector<OriginalPart>& parts, const std::string& main,
                                   const std::string& name, const EncodeChoices& choices) {
  if (!FindPart(parts, main)) {
    return InvalidArgument("the mesh file '" + main + "' is not among the files");
  }
  MW_RETURN_IF_ERROR(FormatFromPath(main).status());
  // The asset reader follows the main file's references (.bin, .mtl,
  // images) among the original's parts, and nowhere else. The set holds
  // what was uploaded or read already (an upload's limit bounded it);
  // choices.limits bound what the reader makes of it.
  MemoryFileSet files;
  for (const OriginalPart& p : parts) {
    MW_RETURN_IF_ERROR(files.Add(p.name, std::string(p.bytes)));
  }
  const bool fidelity = choices.fidelity_db > 0;
  AssetEncodeOptions pipeline;
  pipeline.limits = choices.limits;
  pipeline.semiregular.fidelity_db = choices.fidelity_db;
  pipeline.semiregular.max_vertex_ratio = choices.max_vertex_ratio;
  pipeline.semiregular.threads = choices.threads;
  pipeline.semiregular.force_remesh = choices.force_remesh;
  pipeline.encode.name = name;
  pipeline.encode.threads = choices.threads;
  pipeline.encode.precinct_coefficients = choices.precinct_coefficients;
  pipeline.encode.split_bytes_per_precinct = choices.split_bytes_per_precinct;
  if (fidelity) pipeline.encode.precision = PrecisionForFidelity(choices.fidelity_db);
  pipeline.keep_input_mesh = fidelity;
  pipeline.geometry_if_attributes_unreadable = choices.allow_geometry_only;
  pipeline.original_layer = choices.original_layer;
  auto step = std::chrono::steady_clock::now();
  pipeline.on_read = [&](const AssetRead& read) {
    spdlog::info("{}: read {} vertices, {} faces{} in {:.1f} s", main, read.vertices, read.faces,
                 read.colors ? " with vertex colours" : "", Since(step));
    if (!read.left_out.empty()) spdlog::warn("{}", read.left_out);
    step = std::chrono::steady_clock::now();
  };
  pipeline.on_semiregular = [&](const SemiRegularInput& input) {
    for (const auto& w : input.warnings) spdlog::warn("{}: {}", main, w);
    spdlog::info("{}: {} in {:.1f} s ({} finest vertices, {} remesh attempt(s))", main,
                 input.remeshed ? "remeshed" : "semi-regular as it is", Since(step),
                 input.mesh.positions.size(), input.remesh_attempts);
    step = std::chrono::steady_clock::now();
  };
  MW_ASSIGN_OR_RETURN(AssetEncoding encoded, EncodeAsset(files, main, pipeline));
  const EncodedStream& stream = encoded.stream;
  for (const std::string& note : encoded.bake_notes) spdlog::warn("{}: {}", main, note);
  if (stream.header.texture) {
    const auto& finest = stream.header.texture->maps.front().levels.back();
    spdlog::info("{}: textures baked into a {} x {} atlas, {} map(s)", main, finest.width,
                 finest.height, stream.header.texture->maps.size());
  }
  spdlog::info("{}: encoded {} packets in {:.1f} s", main, stream.packets.size(), Since(step));
  EncodedMesh out;
  if (fidelity) {
    step = std::chrono::steady_clock::now();
    MW_ASSIGN_OR_RETURN(out.fidelity_db,
                        CompleteStreamPsnr(encoded.input_mesh, stream, choices.threads));
    const auto level =
        out.fidelity_db >= choices.fidelity_db ? spdlog::level::info : spdlog::level::warn;
    spdlog::log(level,
                "{}: the complete stream is at {:.2f} dB against the upload (asked {:.2f} dB; "
                "{} finest vertices, precision {}; measured in {:.1f} s)",
                main, out.fidelity_db, choices.fidelity_db, stream.mesh.positions.size(),
                pipeline.encode.precision, Since(step));
  }
  out.container = SerializeFullContainer(stream);
  out.header = stream.header;
  out.packets = stream.packets.size();
  out.remeshed = encoded.semiregular.remeshed;
  return out;
}

Result<IngestResult> IngestOriginal(Catalog& catalog, const std::vector<OriginalPart>& parts,
                                    const std::string& main, const std::string& name,
                                    const EncodeChoices& choices) {
  MW_ASSIGN_OR_RETURN(Original original, DescribeOriginal(parts, main));
  const std::string settings = FormatEncodeSettings(choices);
  const std::string id = MeshIdOf(original.digest, settings, name);
  // The same upload, settings and name: nothing to encode.
  MW_ASSIGN_OR_RETURN(auto existing, catalog.Find(id));
  if (existing) return IngestResult{*existing, true};
  MW_ASSIGN_OR_RETURN(EncodedMesh encoded, EncodeOriginal(parts, main, name, choices));
  CatalogEntry e = EntryFor(encoded);
  e.id = id;
  e.name = name;
  e.source = main;
  e.original = original.digest;
  e.settings = settings;
  MW_ASSIGN_OR_RETURN(IngestResult result, Store(catalog, std::move(e), encoded.container,
                                                 &original, parts));
  result.remeshed = encoded.remeshed;
  result.fidelity_db = encoded.fidelity_db;
  return result;
}

Result<IngestResult> IngestMeshBytes(Catalog& catalog, std::string_view bytes,
                                     const std::string& name, const std::string& source,
                                     const EncodeChoices& choices) {
  return IngestOriginal(catalog, {{source, bytes}}, source, name, choices);
}

Result<IngestResult> IngestMeshFile(Catalog& catalog, const std::filesystem::path& path,
                                    const std::string& name, const EncodeChoices& choices) {
  MW_RETURN_IF_ERROR(FormatFromPath(path).status());
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError("cannot read " + path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  if (!in && !in.eof()) return IoError("cannot read " + path.string());
  const std::string bytes = ss.str();
  const std::string main = path.filename().string();
  std::vector<OriginalPart> parts = {{main, bytes}};
  // A .gltf or .obj refers to files beside it (.bin, .mtl, images): read
  // the asset once to learn which, so that the original kept is complete.
  // When it cannot be read, the ingest says why (and encodes the geometry).
  DirectoryFileSet folder(path.has_parent_path() ? path.parent_path() : ".",
                          choices.limits.max_file_bytes);
  if (HasSidecarFiles(main)) {
    RecordingFileSet recorder(folder);
    (void)ParseMeshAsset(recorder, main, choices.limits);
    for (const std::string& file : recorder.read()) {
      if (file == main) continue;
      MW_ASSIGN_OR_RETURN(const std::string_view sidecar, folder.Read(file));
      parts.push_back({file, sidecar});
    }
  }
  return IngestOriginal(catalog, parts, main, name.empty() ? path.stem().string() : name,
                        choices);
}

Result<IngestResult> IngestContainer(Catalog& catalog, std::string container,
                                     const std::string& name, const std::string& source) {
  MW_ASSIGN_OR_RETURN(ParsedContainer parsed, ParseContainer(container));
  MW_RETURN_IF_ERROR(ValidateStreamHeader(parsed.header));
  if (parsed.ids.size() != parsed.header.packets.length.size()) {
    return ParseError("ingest: the container does not hold every packet");
  }
  EncodedMesh encoded;
  encoded.header = std::move(parsed.header);
  encoded.packets = parsed.ids.size();
  encoded.container = std::move(container);
  CatalogEntry e = EntryFor(encoded);
  e.name = name;
  e.source = source;
  return Store(catalog, std::move(e), encoded.container, nullptr, {});
}

namespace {

// Removes the files of `dir` whose path is not in `keep`, counting
// temporary files apart.
Status SweepFolder(const std::filesystem::path& dir, const std::set<std::filesystem::path>& keep,
                   size_t& orphans, size_t& temps) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return Status::Ok();
  size_t removed = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir, ec)) {
    if (keep.count(f.path())) continue;
    const bool temp = f.path().filename().string().starts_with(kDurableTempPrefix);
    std::error_code rm;
    std::filesystem::remove(f.path(), rm);
    if (rm) return IoError("cannot remove " + f.path().string() + ": " + rm.message());
    ++(temp ? temps : orphans);
    ++removed;
  }
  if (ec) return IoError("cannot list " + dir.string() + ": " + ec.message());
  if (removed > 0) MW_RETURN_IF_ERROR(SyncDirectory(dir));
  return Status::Ok();
}

}  // namespace

Result<CleanupReport> RemoveOrphans(Catalog& catalog, int64_t retired_seconds) {
  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  CleanupReport report;
  MW_ASSIGN_OR_RETURN(std::vector<std::string> expired,
                      catalog.ExpireRetired(NowUnix() - retired_seconds));
  report.expired_containers = expired.size();  // their files go with the orphans below
  MW_ASSIGN_OR_RETURN(std::vector<std::string> paths, catalog.ContainerPaths());
  std::set<std::filesystem::path> keep;
  for (const auto& p : paths) keep.insert(catalog.store_dir() / p);
  MW_RETURN_IF_ERROR(
      SweepFolder(catalog.containers_dir(), keep, report.orphan_files, report.temp_files));
  MW_ASSIGN_OR_RETURN(std::vector<std::string> blobs, catalog.OriginalBlobs());
  keep.clear();
  for (const auto& b : blobs) keep.insert(OriginalBlobPath(catalog.store_dir(), b));
  MW_RETURN_IF_ERROR(SweepFolder(catalog.store_dir() / "originals", keep, report.orphan_originals,
                                 report.temp_files));
  return report;
}

Result<bool> RemoveEntry(Catalog& catalog, const std::string& id) {
  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  MW_ASSIGN_OR_RETURN(auto entry, catalog.Find(id));
  if (!entry) return false;
  std::optional<Original> original;
  if (!entry->original.empty()) {
    MW_ASSIGN_OR_RETURN(original, catalog.FindOriginal(entry->original));
  }
  MW_ASSIGN_OR_RETURN(bool removed, catalog.Remove(id));
  if (!removed) return false;
  std::error_code ec;
  // Another row may name the same container (the same bytes made twice).
  MW_ASSIGN_OR_RETURN(std::vector<std::string> containers, catalog.ContainerPaths());
  if (std::find(containers.begin(), containers.end(), entry->container) == containers.end()) {
    std::filesystem::remove(catalog.ContainerPath(*entry), ec);
    if (ec) spdlog::warn("cannot remove {}: {}", entry->container, ec.message());
  }
  if (original) {
    // The blobs no original of the catalog lists any more.
    MW_ASSIGN_OR_RETURN(std::vector<std::string> blobs, catalog.OriginalBlobs());
    const std::set<std::string> used(blobs.begin(), blobs.end());
    for (const OriginalFile& f : original->files) {
      if (used.count(f.sha256)) continue;
      std::filesystem::remove(OriginalBlobPath(catalog.store_dir(), f.sha256), ec);
      if (ec) spdlog::warn("cannot remove the original file {}: {}", f.name, ec.message());
    }
  }
  return true;
}

}  // namespace meshwave::server
