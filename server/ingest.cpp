#include "ingest.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "core/durable_file.h"
#include "meshwave/mesh_id.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/fidelity.h"
#include "meshwave/mesh_io.h"
#include "meshwave/progression.h"
#include "meshwave/semiregular_input.h"
#include "sha256.h"

namespace meshwave::server {
namespace {

int64_t NowUnix() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Result<IngestResult> Store(Catalog& catalog, const std::string& container,
                           const StreamHeader& header, size_t packets,
                           const std::string& name, const std::string& source) {
  CatalogEntry e;
  e.sha256 = Sha256Hex(container);
  e.id = MeshIdFromSha256(e.sha256);
  e.name = name;
  e.source = source;
  e.vertices = header.vertices;
  e.faces = header.faces;
  e.levels = header.transform.levels;
  e.packets = static_cast<uint32_t>(packets);
  e.bytes = container.size();
  e.container = "containers/" + e.sha256 + ".mwv";
  e.created_unix = NowUnix();

  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  MW_ASSIGN_OR_RETURN(auto existing, catalog.Find(e.id));
  if (existing) {
    if (existing->sha256 != e.sha256) {
      return Status(StatusCode::kInternal,
                    "ingest: id " + e.id + " already names another container");
    }
    return IngestResult{*existing, true, false};
  }
  MW_RETURN_IF_ERROR(WriteFileDurably(catalog.ContainerPath(e), container));
  if (Status s = catalog.Insert(e); !s.ok()) {
    // No row names the file (under the ingest lock, nobody else wrote it):
    // remove it, or a full disk would keep the space and leave an orphan
    // (found by FaultTest.DiskFullDuringIngest...).
    std::error_code ec;
    std::filesystem::remove(catalog.ContainerPath(e), ec);
    return s;
  }
  return IngestResult{e, false, false};
}

}  // namespace

Result<IngestResult> IngestContainer(Catalog& catalog, std::string container,
                                     const std::string& name,
                                     const std::string& source) {
  MW_ASSIGN_OR_RETURN(ParsedContainer parsed, ParseContainer(container));
  MW_RETURN_IF_ERROR(ValidateStreamHeader(parsed.header));
  if (parsed.ids.size() != parsed.header.packets.length.size()) {
    return ParseError("ingest: the container does not hold every packet");
  }
  return Store(catalog, container, parsed.header, parsed.ids.size(), name, source);
}

Result<IngestResult> IngestMeshBytes(Catalog& catalog, std::string_view bytes,
                                     MeshFormat format, const std::string& name,
                                     const std::string& source, const EncodeChoices& choices) {
  MW_ASSIGN_OR_RETURN(TriMesh mesh, ParseMesh(bytes, format, source));
  const bool fidelity = choices.fidelity_db > 0;
  const TriMesh original = fidelity ? mesh : TriMesh{};
  SemiRegularInputOptions input_options;
  input_options.fidelity_db = choices.fidelity_db;
  input_options.max_vertex_ratio = choices.max_vertex_ratio;
  input_options.threads = choices.threads;
  input_options.force_remesh = choices.force_remesh;
  MW_ASSIGN_OR_RETURN(SemiRegularInput input, ToSemiRegular(std::move(mesh), input_options));
  for (const auto& w : input.warnings) spdlog::warn("{}: {}", source, w);
  EncodeOptions options;
  options.name = name;
  options.threads = choices.threads;
  options.precinct_coefficients = choices.precinct_coefficients;
  options.split_bytes_per_precinct = choices.split_bytes_per_precinct;
  if (fidelity) options.precision = PrecisionForFidelity(choices.fidelity_db);
  MW_ASSIGN_OR_RETURN(EncodedStream stream, EncodeMesh(input.mesh, options));
  double reached = 0;
  if (fidelity) {
    MW_ASSIGN_OR_RETURN(reached, CompleteStreamPsnr(original, stream, choices.threads));
    const auto level = reached >= choices.fidelity_db ? spdlog::level::info : spdlog::level::warn;
    spdlog::log(level,
                "{}: the complete stream is at {:.2f} dB against the upload (asked {:.2f} dB; "
                "{} finest vertices after {} remesh attempt(s), precision {})",
                source, reached, choices.fidelity_db, input.finest_vertices,
                input.remesh_attempts, options.precision);
  }
  const std::string container = SerializeFullContainer(stream);
  MW_ASSIGN_OR_RETURN(IngestResult result,
                      Store(catalog, container, stream.header, stream.packets.size(), name, source));
  result.remeshed = input.remeshed;
  result.fidelity_db = reached;
  return result;
}

Result<IngestResult> IngestMeshFile(Catalog& catalog,
                                    const std::filesystem::path& path,
                                    const std::string& name, const EncodeChoices& choices) {
  MW_ASSIGN_OR_RETURN(MeshFormat format, FormatFromPath(path));
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError("cannot read " + path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  if (!in && !in.eof()) return IoError("cannot read " + path.string());
  return IngestMeshBytes(catalog, ss.str(), format,
                         name.empty() ? path.stem().string() : name,
                         path.filename().string(), choices);
}

Result<CleanupReport> RemoveOrphans(Catalog& catalog) {
  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  MW_ASSIGN_OR_RETURN(std::vector<std::string> paths, catalog.ContainerPaths());
  std::set<std::filesystem::path> known;
  for (const auto& p : paths) known.insert(catalog.store_dir() / p);
  CleanupReport report;
  std::error_code ec;
  for (const auto& f : std::filesystem::directory_iterator(catalog.containers_dir(), ec)) {
    if (known.count(f.path())) continue;
    const bool temp = f.path().filename().string().starts_with(kDurableTempPrefix);
    std::error_code rm;
    std::filesystem::remove(f.path(), rm);
    if (rm) return IoError("cannot remove " + f.path().string() + ": " + rm.message());
    ++(temp ? report.temp_files : report.orphan_files);
  }
  if (ec) return IoError("cannot list " + catalog.containers_dir().string() + ": " + ec.message());
  if (report.orphan_files + report.temp_files > 0) {
    MW_RETURN_IF_ERROR(SyncDirectory(catalog.containers_dir()));
  }
  return report;
}

Result<bool> RemoveEntry(Catalog& catalog, const std::string& id) {
  MW_ASSIGN_OR_RETURN(auto lock, catalog.LockIngest());
  MW_ASSIGN_OR_RETURN(auto entry, catalog.Find(id));
  if (!entry) return false;
  MW_ASSIGN_OR_RETURN(bool removed, catalog.Remove(id));
  if (!removed) return false;
  std::error_code ec;
  std::filesystem::remove(catalog.ContainerPath(*entry), ec);
  if (ec) spdlog::warn("cannot remove {}: {}", entry->container, ec.message());
  return true;
}

}  // namespace meshwave::server
