// meshwave-server: serves a catalog of progressive meshes over HTTP, and
// `meshwave-server ingest` fills the catalog from mesh files.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "ingest.h"
#include "server.h"
#include "server_config.h"

namespace meshwave::server {
namespace {

int Fail(const std::string& what, const Status& s) {
  std::fprintf(stderr, "meshwave-server%s: %s\n", what.c_str(), s.ToString().c_str());
  return 1;
}

int Serve(const std::string& catalog, const std::string& listen, const std::string& config_path,
          unsigned threads, const std::string& port_file) {
  ServeOptions options;
  options.catalog_dir = catalog;
  options.port_file = port_file;
  if (!config_path.empty()) {
    auto config = LoadServerConfig(config_path);
    if (!config.ok()) return Fail("", config.status());
    options.config = std::move(*config);
  }
  if (!listen.empty()) options.config.set_listen(listen);
  if (threads > 0) options.config.set_threads(threads);
  if (Status s = FinishServerConfig(options.config); !s.ok()) return Fail("", s);
  if (Status s = RunServer(options); !s.ok()) return Fail("", s);
  return 0;
}

int Ingest(const std::string& catalog_dir, const std::vector<std::string>& files,
           const std::string& name) {
  if (!name.empty() && files.size() != 1) {
    return Fail(" ingest", InvalidArgument("--name needs exactly one file"));
  }
  auto catalog = Catalog::Open(catalog_dir);
  if (!catalog.ok()) return Fail(" ingest", catalog.status());
  auto cleanup = RemoveOrphans(**catalog);
  if (!cleanup.ok()) return Fail(" ingest", cleanup.status());
  int exit_code = 0;
  for (const auto& file : files) {
    auto result = IngestMeshFile(**catalog, file, name);
    if (!result.ok()) {
      exit_code = Fail(" ingest", result.status().WithContext(file));
      continue;
    }
    const CatalogEntry& e = result->entry;
    std::printf("%s %s: %s (%llu vertices, %u levels, %u packets, %llu bytes)%s\n",
                e.id.c_str(), file.c_str(), result->already_present ? "already present" : "ingested",
                static_cast<unsigned long long>(e.vertices), e.levels, e.packets,
                static_cast<unsigned long long>(e.bytes), result->remeshed ? ", remeshed" : "");
    std::fflush(stdout);
  }
  return exit_code;
}

}  // namespace
}  // namespace meshwave::server

int main(int argc, char** argv) {
  using namespace meshwave::server;
  CLI::App app{"meshwave-server: streams progressive meshes over HTTP from a catalog"};
  std::string catalog, listen, config, port_file, log_level = "info";
  unsigned threads = 0;
  app.add_option("--catalog", catalog, "Catalog directory (created when missing)");
  app.add_option("--listen", listen, "host:port to listen on; port 0 picks a free port "
                                     "(default 127.0.0.1:8080)");
  app.add_option("--config", config, "Configuration file (protobuf text format, docs/API.md)");
  app.add_option("--threads", threads, "I/O threads (default 2)")->check(CLI::Range(1, 256));
  app.add_option("--port-file", port_file, "Write the bound port to this file");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();

  std::string ingest_catalog, ingest_name;
  std::vector<std::string> files;
  CLI::App* ingest = app.add_subcommand(
      "ingest", "Encode mesh files into the catalog (irregular meshes are remeshed first)");
  ingest->add_option("--catalog", ingest_catalog, "Catalog directory (created when missing)")
      ->required();
  ingest->add_option("files", files, "Mesh files (.ply, .obj, .off)")->required();
  ingest->add_option("--name", ingest_name, "Name of the entry (one file only; default: "
                                            "the file's stem)");
  app.require_subcommand(0, 1);
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));

  if (*ingest) return Ingest(ingest_catalog, files, ingest_name);
  if (catalog.empty()) {
    std::fprintf(stderr, "meshwave-server: --catalog is required (see --help)\n");
    return 2;
  }
  return Serve(catalog, listen, config, threads, port_file);
}
