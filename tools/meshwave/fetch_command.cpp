// meshwave fetch URL --out FILE: a mesh from a meshwave-server at a budget.
#include <iostream>
#include <memory>

#include "cli_util.h"
#include "client_options.h"
#include "commands.h"
#include "fetch_output.h"
#include "meshwave/client/blocking_session.h"
#include "meshwave/client/local_state.h"
#include "meshwave/stream_limits.h"
#include "region_fetch.h"

namespace meshwave::cli {
namespace {

struct FetchArgs {
  std::string url, budget, rate, deadline, order = "quality", state;
  double psnr = 0;
  int max_level = -1;
  bool websocket = false;
  FetchOutputOptions output;
  ClientArgs client;
  DecodeLimitArgs limits;
  RegionRequestArgs region;
};

Result<client::Budget> BudgetFrom(const FetchArgs& a) {
  const int kinds = !a.budget.empty() +
                    (!a.rate.empty() || !a.deadline.empty()) + (a.psnr > 0);
  if (kinds > 1)
    return InvalidArgument(
        "give one of --budget, --rate/--deadline and --psnr");
  if (!a.budget.empty()) {
    MW_ASSIGN_OR_RETURN(uint64_t bytes, ParseByteSize(a.budget));
    return client::Budget::Bytes(bytes);
  }
  if (!a.rate.empty() || !a.deadline.empty()) {
    if (a.rate.empty() || a.deadline.empty()) {
      return InvalidArgument("--rate and --deadline go together");
    }
    MW_ASSIGN_OR_RETURN(double rate, client::ParseRate(a.rate));
    MW_ASSIGN_OR_RETURN(double seconds, client::ParseDuration(a.deadline));
    MW_ASSIGN_OR_RETURN(uint64_t bytes, client::RateBudgetBytes(rate, seconds));
    return client::Budget::Bytes(bytes);
  }
  if (a.psnr > 0) return client::Budget::Psnr(a.psnr);
  return client::Budget::All();
}

Status SaveSessionState(const std::string& path, const client::MeshUrl& url,
                        const client::Session& session) {
  client::LocalState state;
  state.url = url;
  state.order = session.options().order;
  state.max_level = session.options().max_level;
  state.cursor = session.progress().packets;
  state.budget_bytes = session.budget_bytes();
  state.container = session.Container();
  state.served_container = session.ServedContainer();
  return client::SaveState(path, state);
}

Status Run(const FetchArgs& args) {
  MW_ASSIGN_OR_RETURN(client::MeshUrl url, client::ParseMeshUrl(args.url));
  if (args.websocket) url.server.websocket = true;  // http -> ws, https -> wss
  MW_ASSIGN_OR_RETURN(client::Budget budget, BudgetFrom(args));
  client::SessionOptions options;
  MW_ASSIGN_OR_RETURN(options.order, ParseProgression(args.order));
  options.max_level = args.max_level;
  client::TransportOptions transport;
  MW_RETURN_IF_ERROR(ApplyClientOptions(args.client, transport, options.retry));
  MW_RETURN_IF_ERROR(ApplyDecodeLimitOptions(args.limits, options));
  FetchOutputOptions output_options = args.output;
  output_options.max_level = args.max_level;
  MW_ASSIGN_OR_RETURN(auto output, FetchOutput::Create(output_options));
  MW_ASSIGN_OR_RETURN(std::optional<Region> region, RegionFrom(args.region));
  if (region) {
    // Units, region first: the budget counts the header as a container's.
    if (budget.kind == client::Budget::Kind::kPsnr) {
      return InvalidArgument("--psnr does not go with --region or --view: give --budget");
    }
    client::RegionSession session(url, options, transport);
    return RunRegionFetch(session, url, region,
                          budget.kind == client::Budget::Kind::kBytes
                              ? std::optional<uint64_t>(budget.bytes)
                              : std::nullopt,
                          /*budget_counts_header=*/true, *output, args.state);
  }
  auto blocking = std::make_unique<client::BlockingSession>(url, options, transport);
  Status fetched = blocking->Fetch(budget, output->Handler());
  if (fetched.code() == StatusCode::kStale) {
    // Re-encoded between two requests of this fetch: once more, from the
    // new container.
    std::cerr << "meshwave fetch: " << fetched.message() << "\nmeshwave fetch: starting over\n";
    blocking = std::make_unique<client::BlockingSession>(url, options, transport);
    fetched = blocking->Fetch(budget, output->Handler());
  }
  client::Session& session = blocking->session();
  if (!fetched.ok()) {
    // Keep what arrived intact: `meshwave refine` continues from it.
    if (!args.state.empty() && session.has_header() &&
        session.progress().packets > 0 &&
        SaveSessionState(args.state, url, session).ok()) {
      std::cerr << "meshwave fetch: kept the " << session.progress().packets
                << " packets received in " << args.state << "\n";
    }
    return fetched.WithContext(url.ToString());
  }
  if (!args.state.empty())
    MW_RETURN_IF_ERROR(SaveSessionState(args.state, url, session));
  return output->Finish(session, url.ToString(), args.state);
}

}  // namespace

void AddFetchCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<FetchArgs>();
  CLI::App* cmd = app.add_subcommand("fetch",
                                     "Fetch a mesh from a meshwave-server at a "
                                     "budget, decoding as packets arrive");
  cmd->add_option("url", args->url,
                  "Mesh URL: http(s)://host:port/v1/meshes/{id}, or ws(s):// "
                  "for WebSocket")
      ->required();
  cmd->add_flag("--ws", args->websocket,
                "Stream over WebSocket (GET /v1/ws) even with an http(s) URL");
  cmd->add_option("--budget", args->budget,
                  "Bytes of the stream, header included (e.g. 20000, 64KiB)");
  cmd->add_option("--rate", args->rate,
                  "Link rate (e.g. 2Mbit, 500kbit, 1MB/s), with --deadline");
  cmd->add_option("--deadline", args->deadline,
                  "Time to fill at --rate (e.g. 1.5s, 200ms)");
  cmd->add_option("--psnr", args->psnr,
                  "Stop once the estimated PSNR (dB, from the packet index) "
                  "reaches this")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--order", args->order,
                  "Packet order: quality, resolution or rd")
      ->check(CLI::IsMember({"quality", "resolution", "rd"}))
      ->capture_default_str();
  cmd->add_option(
         "--max-level", args->max_level,
         "Only subbands below this level (a coarser mesh for small devices)")
      ->check(CLI::Range(0, kMaxStreamLevels));
  AddFetchOutputOptions(cmd, args->output, "Output mesh (.ply, .obj, .glb or .gltf)",
                        /*out_required=*/true);
  cmd->add_option("--state", args->state,
                  "Keep the packets received as a partial container FILE (and "
                  "FILE.session) "
                  "for `meshwave refine`");
  AddRegionOptions(cmd, args->region);
  AddClientOptions(cmd, args->client);
  AddDecodeLimitOptions(cmd, args->limits);
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("fetch", s);
  });
}

}  // namespace meshwave::cli
