// meshwave-server: serves a catalog of progressive meshes over HTTP, and
// `meshwave-server ingest` fills the catalog from mesh files.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "bulk_ingest.h"
#include "ingest.h"
#include "reencode.h"
#include "upload_worker.h"
#include "server.h"
#include "server_config.h"

namespace meshwave::server {
namespace {

int Fail(const std::string& what, const Status& s) {
  std::fprintf(stderr, "meshwave-server%s: %s\n", what.c_str(), s.ToString().c_str());
  return 1;
}

int Serve(const std::string& catalog, const std::string& store, const std::string& listen,
          const std::string& config_path, unsigned threads, const std::string& port_file,
          const std::string& viewer_dir) {
  ServeOptions options;
  options.catalog = catalog;
  options.store = store;
  options.port_file = port_file;
  if (!config_path.empty()) {
    auto config = LoadServerConfig(config_path);
    if (!config.ok()) return Fail("", config.status());
    options.config = std::move(*config);
  }
  if (!listen.empty()) options.config.set_listen(listen);
  if (threads > 0) options.config.set_threads(threads);
  if (!viewer_dir.empty()) options.config.set_viewer_dir(viewer_dir);
  if (Status s = FinishServerConfig(options.config); !s.ok()) return Fail("", s);
  if (Status s = RunServer(options); !s.ok()) return Fail("", s);
  return 0;
}

struct IngestOptions {
  std::string catalog, store, name, list, shard = "0/1";
  std::vector<std::string> inputs;
  unsigned jobs = 1;
  EncodeChoices choices;
};

int Ingest(const IngestOptions& o) {
  auto shard = ParseShard(o.shard);
  if (!shard.ok()) return Fail(" ingest", shard.status());
  auto all = CollectMeshFiles(o.inputs, o.list);
  if (!all.ok()) return Fail(" ingest", all.status());
  const std::vector<std::filesystem::path> files = FilesOfShard(*all, *shard);
  if (!o.name.empty() && files.size() != 1) {
    return Fail(" ingest", InvalidArgument("--name needs exactly one file"));
  }
  auto catalog = Catalog::Open(o.catalog, o.store);
  if (!catalog.ok()) return Fail(" ingest", catalog.status());
  auto cleanup = RemoveOrphans(**catalog);
  if (!cleanup.ok()) return Fail(" ingest", cleanup.status());
  if (shard->count > 1) {
    std::fprintf(stderr, "meshwave-server ingest: shard %u/%u: %zu of %zu files\n", shard->index,
                 shard->count, files.size(), all->size());
  }
  const size_t failed = IngestFiles(
      **catalog, files, o.jobs, o.name,
      [](const std::filesystem::path& file, const Result<IngestResult>& result) {
        if (!result.ok()) {
          Fail(" ingest", result.status().WithContext(file.string()));
          return;
        }
        const CatalogEntry& e = result->entry;
        std::printf("%s %s: %s (%llu vertices, %u levels, %u packets, %llu bytes)%s",
                    e.id.c_str(), file.c_str(),
                    result->already_present ? "already present" : "ingested",
                    static_cast<unsigned long long>(e.vertices), e.levels, e.packets,
                    static_cast<unsigned long long>(e.bytes), result->remeshed ? ", remeshed" : "");
        if (result->fidelity_db > 0) {
          std::printf(", complete stream %.2f dB against the file", result->fidelity_db);
        }
        std::printf("\n");
        std::fflush(stdout);
      },
      o.choices);
  return failed == 0 ? 0 : 1;
}

struct UploadCommand {
  std::string catalog, store, name, source, boundary;
  EncodeChoices choices;
};

// The worker process of an upload (worker_process.h): the mesh file (or a
// multipart body of files, with --boundary) on standard input, the outcome on standard output (upload_worker.h).
int IngestUpload(const UploadCommand& c) {
  // Standard output carries the outcome alone; log lines go to the server.
  spdlog::set_default_logger(spdlog::stderr_color_mt("ingest-upload"));
  std::string bytes;
  char buffer[1 << 16];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0;) bytes.append(buffer, n);
  auto catalog = Catalog::Open(c.catalog, c.store);
  Result<IngestResult> result =
      catalog.ok() ? IngestUpload(**catalog, bytes, c.name, c.source, c.boundary, c.choices)
                   : Result<IngestResult>(catalog.status());
  std::fputs(FormatUploadOutcome(result).c_str(), stdout);
  std::fflush(stdout);
  return result.ok() ? 0 : 3;
}

struct ReencodeCommand {
  std::string catalog, store, shard = "0/1";
  ReencodeOptions options;
  int64_t keep_retired_seconds = kDefaultRetiredSeconds;
};

const char* ActionText(ReencodeAction a) {
  switch (a) {
    case ReencodeAction::kCurrent: return "current";
    case ReencodeAction::kReencoded: return "re-encoded";
    case ReencodeAction::kNoOriginal: return "kept as it is";
    case ReencodeAction::kWouldReencode: return "would be re-encoded";
    case ReencodeAction::kChanged: return "left alone";
    case ReencodeAction::kFailed: return "failed";
  }
  return "?";
}

int Reencode(ReencodeCommand c) {
  auto shard = ParseShard(c.shard);
  if (!shard.ok()) return Fail(" reencode", shard.status());
  c.options.shard = *shard;
  auto catalog = Catalog::Open(c.catalog, c.store);
  if (!catalog.ok()) return Fail(" reencode", catalog.status());
  if (!c.options.dry_run) {
    auto cleanup = RemoveOrphans(**catalog, c.keep_retired_seconds);
    if (!cleanup.ok()) return Fail(" reencode", cleanup.status());
  }
  auto report = ReencodeCatalog(
      **catalog, c.options, [](size_t i, size_t n, const ReencodeStep& step) {
        const CatalogEntry& e = step.before;
        if (step.action == ReencodeAction::kCurrent) return;
        std::printf("[%zu/%zu] %s %s: %s", i + 1, n, e.id.c_str(), e.name.c_str(),
                    ActionText(step.action));
        if (step.action == ReencodeAction::kReencoded) {
          std::printf(" in %.1f s (%llu -> %llu bytes, format version %u)", step.seconds,
                      static_cast<unsigned long long>(e.bytes),
                      static_cast<unsigned long long>(step.after.bytes),
                      step.after.format_version);
        }
        if (!step.why.empty()) std::printf(": %s", step.why.c_str());
        std::printf("\n");
        std::fflush(stdout);
      });
  if (!report.ok()) return Fail(" reencode", report.status());
  std::printf("reencode: %zu meshes: %zu %s, %zu current, %zu without an original, %zu changed "
              "meanwhile, %zu failed\n",
              report->meshes, report->reencoded,
              c.options.dry_run ? "would be re-encoded" : "re-encoded", report->current,
              report->no_original, report->changed, report->failed);
  return report->failed == 0 ? 0 : 1;
}

}  // namespace
}  // namespace meshwave::server

int main(int argc, char** argv) {
  using namespace meshwave::server;
  CLI::App app{"meshwave-server: streams progressive meshes over HTTP from a catalog"};
  std::string catalog, store, listen, config, port_file, viewer_dir, log_level = "info";
  unsigned threads = 0;
  app.add_option("--catalog", catalog, "Catalog: a directory (SQLite, created when missing) or "
                                       "postgres://USER@HOST:PORT/DB (password from PGPASSWORD)")
      ->envname("MESHWAVE_CATALOG");
  app.add_option("--store", store, "Container store shared by the replicas (postgres:// "
                                   "catalogs only)")
      ->envname("MESHWAVE_STORE");
  app.add_option("--listen", listen, "host:port to listen on; port 0 picks a free port "
                                     "(default 127.0.0.1:8080)");
  app.add_option("--config", config, "Configuration file (protobuf text format, docs/API.md)");
  app.add_option("--threads", threads, "I/O threads (default 2)")->check(CLI::Range(1, 256));
  app.add_option("--port-file", port_file, "Write the bound port to this file");
  app.add_option("--viewer-dir", viewer_dir,
                 "Directory of the browser viewer served under /viewer/ (default: the installed "
                 "share/meshwave/viewer, else the build tree's copy)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();

  IngestOptions ingest_options;
  CLI::App* ingest = app.add_subcommand(
      "ingest", "Encode mesh files into the catalog (irregular meshes are remeshed first)");
  ingest->add_option("--catalog", ingest_options.catalog, "Catalog directory or postgres:// URI")
      ->envname("MESHWAVE_CATALOG")
      ->required();
  ingest->add_option("--store", ingest_options.store, "Container store (postgres:// only)")
      ->envname("MESHWAVE_STORE");
  ingest->add_option("inputs", ingest_options.inputs,
                     "Mesh files (.ply, .obj, .off, .glb, .gltf) or folders searched recursively");
  ingest->add_option("--list", ingest_options.list, "File listing mesh files, one per line");
  ingest->add_option("--fidelity", ingest_options.choices.fidelity_db,
                     "Symmetric surface PSNR (dB) each complete stream should reach against its "
                     "file: denser remesh and finer precision until it does (meshwave encode "
                     "--fidelity); prints what it reached. Default: about what Draco's default "
                     "quantisation gives; 0: one remesh at about the file's density")
      ->check(CLI::Range(0.0, 200.0))
      ->capture_default_str();
  ingest->add_option("--max-vertex-ratio", ingest_options.choices.max_vertex_ratio,
                     "The densest remesh --fidelity may make, in finest vertices per input vertex")
      ->check(CLI::Range(1.0, 64.0))
      ->capture_default_str();
  ingest->add_option("--jobs", ingest_options.jobs, "Meshes encoded in parallel")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  ingest->add_option("--threads", ingest_options.choices.threads,
                     "Threads remeshing and encoding each mesh (0: the machine's cores divided "
                     "by --jobs, at least 1); the containers are the same for any number")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  ingest->add_flag("--remesh", ingest_options.choices.force_remesh,
                   "Remesh even meshes that are already semi-regular (meshwave encode --remesh)");
  ingest->add_flag("--allow-geometry-only", ingest_options.choices.allow_geometry_only,
                   "When a file's textures or attributes cannot be read (a missing image, a bad "
                   "UV index, ...) but its geometry can: store the geometry alone, with a "
                   "warning, instead of refusing the file");
  ingest->add_flag("!--no-original", ingest_options.choices.original_layer,
                   "Leave out the final layer that restores each mesh's own connectivity and "
                   "positions (docs/FORMAT.md 2.5): the stream ends in the remesh");
  ingest->add_option("--precinct-size", ingest_options.choices.precinct_coefficients,
                     "Precincts, so that region requests can refine one part first: base faces "
                     "grouped into runs of at least this many coefficients per subband "
                     "(meshwave encode --precinct-size); 0: none")
      ->check(CLI::Range(0u, 1u << 30))
      ->capture_default_str();
  ingest->add_option("--split-bytes", ingest_options.choices.split_bytes_per_precinct,
                     "Packets are split into one codeword per precinct where the precincts "
                     "would average at least this many bytes (meshwave encode --split-bytes)")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  ingest->add_option("--shard", ingest_options.shard,
                     "I/N: only the files of shard I of N (one per worker of a Job)")
      ->capture_default_str();
  ingest->add_option("--name", ingest_options.name, "Name of the entry (one file only; default: "
                                                    "the file's stem)");
  ReencodeCommand reencode_command;
  CLI::App* reencode = app.add_subcommand(
      "reencode",
      "Re-encode the meshes whose container is of an older stream format version (or was made "
      "with other settings than given here) from their originals, swapping each new container "
      "in atomically while the old one is served; safe to interrupt and run again");
  reencode->add_option("--catalog", reencode_command.catalog, "Catalog directory or postgres:// URI")
      ->envname("MESHWAVE_CATALOG")
      ->required();
  reencode->add_option("--store", reencode_command.store, "Container store (postgres:// only)")
      ->envname("MESHWAVE_STORE");
  SettingsChange& change = reencode_command.options.change;
  reencode->add_option("--fidelity", change.fidelity_db,
                       "Re-encode every mesh to this fidelity (dB; ingest --fidelity)")
      ->check(CLI::Range(0.0, 200.0));
  reencode->add_option("--max-vertex-ratio", change.max_vertex_ratio,
                       "Densest remesh --fidelity may make (ingest --max-vertex-ratio)")
      ->check(CLI::Range(1.0, 64.0));
  reencode->add_option("--precinct-size", change.precinct_coefficients,
                       "Re-encode every mesh with this precinct size (ingest --precinct-size)")
      ->check(CLI::Range(0u, 1u << 30));
  reencode->add_option("--split-bytes", change.split_bytes_per_precinct,
                       "Re-encode every mesh with this split size (ingest --split-bytes)")
      ->check(CLI::Range(1u, 1u << 20));
  reencode->add_option("--threads", reencode_command.options.threads,
                       "Threads encoding each mesh (0: the machine's cores)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  reencode->add_option("--keep-retired", reencode_command.keep_retired_seconds,
                       "Seconds a replaced container stays on disk for readers that may still "
                       "open it (other replicas) before a later run removes it")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40))
      ->capture_default_str();
  reencode->add_option("--shard", reencode_command.shard,
                       "I/N: only the meshes of shard I of N, by a hash of their id (one per "
                       "worker of a Job)")
      ->capture_default_str();
  reencode->add_flag("--dry-run", reencode_command.options.dry_run,
                     "Say what would be re-encoded and why, change nothing");
  UploadCommand upload_command;
  CLI::App* upload = app.add_subcommand(
      "ingest-upload", "The server's upload worker: ingests the mesh file on standard input");
  upload->group("");  // run by the server (worker_process.h), not by people
  upload->add_option("--catalog", upload_command.catalog)->required();
  upload->add_option("--store", upload_command.store);
  upload->add_option("--name", upload_command.name)->required();
  upload->add_option("--source", upload_command.source)->required();
  upload->add_option("--fidelity", upload_command.choices.fidelity_db);
  upload->add_option("--max-vertex-ratio", upload_command.choices.max_vertex_ratio);
  upload->add_option("--threads", upload_command.choices.threads);
  upload->add_option("--boundary", upload_command.boundary);  // a multipart body (upload_files.h)
  upload->add_option("--max-file-bytes", upload_command.choices.limits.max_file_bytes);
  upload->add_option("--max-image-bytes", upload_command.choices.limits.max_image_bytes);
  upload->add_option("--max-image-pixels", upload_command.choices.limits.max_image_pixels);
  app.require_subcommand(0, 1);
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));

  if (*ingest) {
    if (ingest_options.inputs.empty() && ingest_options.list.empty()) {
      std::fprintf(stderr, "meshwave-server ingest: give mesh files, folders or --list\n");
      return 2;
    }
    return Ingest(ingest_options);
  }
  if (*reencode) return Reencode(reencode_command);
  if (*upload) return IngestUpload(upload_command);
  if (catalog.empty()) {
    std::fprintf(stderr, "meshwave-server: --catalog is required (see --help)\n");
    return 2;
  }
  return Serve(catalog, store, listen, config, threads, port_file, viewer_dir);
}
