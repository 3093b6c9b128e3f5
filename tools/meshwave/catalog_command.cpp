// meshwave catalog URL: the meshes a meshwave-server hosts.
#include <cstdio>

#include "cli_util.h"
#include "client_options.h"
#include "commands.h"
#include "meshwave/client/catalog.h"

namespace meshwave::cli {
namespace {

struct CatalogArgs {
  std::string url;
  bool json = false;
  ClientArgs client;
};

Status Run(const CatalogArgs& args) {
  MW_ASSIGN_OR_RETURN(client::ServerUrl server,
                      client::ParseServerUrl(args.url));
  client::TransportOptions transport;
  client::RetryPolicy unused;
  MW_RETURN_IF_ERROR(ApplyClientOptions(args.client, transport, unused));
  auto list = client::ListCatalog(server, transport);
  if (!list.ok()) return list.status().WithContext(server.ToString());
  if (args.json) {
    PrintJson(*list);
    return Status::Ok();
  }
  std::printf("%-12s  %-20s %9s %9s %6s %7s %10s\n", "id", "name", "vertices",
              "faces", "levels", "packets", "bytes");
  for (const auto& m : list->meshes()) {
    std::printf("%-12s  %-20s %9llu %9llu %6u %7u %10llu\n", m.id().c_str(),
                m.name().c_str(), static_cast<unsigned long long>(m.vertices()),
                static_cast<unsigned long long>(m.faces()), m.levels(),
                m.packets(), static_cast<unsigned long long>(m.bytes()));
  }
  std::printf(
      "%d meshes; fetch one with: meshwave fetch %s/v1/meshes/ID --out "
      "mesh.ply\n",
      list->meshes_size(), server.ToString().c_str());
  return Status::Ok();
}

}  // namespace

void AddCatalogCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CatalogArgs>();
  CLI::App* cmd =
      app.add_subcommand("catalog", "List the meshes a meshwave-server hosts");
  cmd->add_option("url", args->url, "Server URL: http(s)://host:port")
      ->required();
  cmd->add_flag("--json", args->json, "Print the listing as JSON");
  AddClientOptions(cmd, args->client);
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("catalog", s);
  });
}

}  // namespace meshwave::cli
