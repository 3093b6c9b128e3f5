// meshwave refine STATE --more SIZE: the next packets of a fetched mesh.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli_util.h"
#include "client_options.h"
#include "commands.h"
#include "fetch_output.h"
#include "meshwave/client/blocking_session.h"
#include "meshwave/client/local_state.h"
#include "region_fetch.h"

namespace meshwave::cli {
namespace {

struct RefineArgs {
  std::string state, more;
  FetchOutputOptions output;
  ClientArgs client;
  DecodeLimitArgs limits;
  RegionRequestArgs region;
};

// The mesh was re-encoded since the state was saved: what it holds cannot
// be continued (docs/API.md, "Re-encoded meshes").
void ReportStartingOver(const Status& stale, const std::string& state_path) {
  std::cerr << "meshwave refine: " << stale.message() << "\n"
            << "meshwave refine: " << state_path
            << " belongs to the old container: starting over from the new one\n";
}

// A session of units, or one of packets asked for a region: the units the
// region (given, or the state's last) puts first, `more` bytes of them.
Status RunUnits(const RefineArgs& args, const client::LocalState& state,
                const client::SessionOptions& options, const client::TransportOptions& transport,
                uint64_t more, FetchOutput& output) {
  std::optional<Region> region;
  if (args.region.given()) {
    MW_ASSIGN_OR_RETURN(region, RegionFrom(args.region));
  } else {
    auto kept = RegionFromStateText(state.region);
    if (!kept.ok()) return kept.status().WithContext("state " + args.state);
    region = *kept;
  }
  {
    client::RegionSession session(state.url, options, transport);
    Status restored = session.Restore(state.container, state.parts);
    if (restored.ok() && state.units && session.HeldText() != state.held) {
      restored = ParseError("the held units differ from what its files hold (they do not belong together)");
    }
    if (!restored.ok()) return restored.WithContext("state " + args.state);
    if (!state.served_container.empty()) session.PinContainer(state.served_container);
    const Status s = RunRegionFetch(session, state.url, region, more,
                                    /*budget_counts_header=*/false, output, args.state);
    if (s.code() != StatusCode::kStale) return s;
    ReportStartingOver(s, args.state);
  }
  // What was held, and the more asked for, from the new container.
  client::RegionSession fresh(state.url, options, transport);
  return RunRegionFetch(fresh, state.url, region, state.budget_bytes + more,
                        /*budget_counts_header=*/false, output, args.state);
}

Status Run(const RefineArgs& args) {
  MW_ASSIGN_OR_RETURN(uint64_t more, ParseByteSize(args.more));
  MW_ASSIGN_OR_RETURN(client::LocalState state, client::LoadState(args.state));
  client::SessionOptions options;
  options.order = state.order;
  options.max_level = state.max_level;
  client::TransportOptions transport;
  MW_RETURN_IF_ERROR(ApplyClientOptions(args.client, transport, options.retry));
  MW_RETURN_IF_ERROR(ApplyDecodeLimitOptions(args.limits, options));
  FetchOutputOptions output_options = args.output;
  if (output_options.out.empty()) {
    output_options.out = std::filesystem::path(args.state).replace_extension(".ply").string();
  }
  output_options.max_level = state.max_level;
  MW_ASSIGN_OR_RETURN(auto output, FetchOutput::Create(output_options));
  if (state.units || args.region.given()) {
    return RunUnits(args, state, options, transport, more, *output);
  }
  auto blocking = std::make_unique<client::BlockingSession>(state.url, options, transport);
  Status restored = blocking->session().Restore(state.container, state.budget_bytes);
  if (!restored.ok()) return restored.WithContext("state " + args.state);
  if (!state.served_container.empty()) blocking->session().PinContainer(state.served_container);

  // The budget grows by --more: refining after a fetch of B gives what a
  // fetch of B + more gives, and the packets held are never asked for.
  const client::Budget budget = client::Budget::Bytes(state.budget_bytes + more);
  Status fetched = blocking->Fetch(budget, output->Handler());
  if (fetched.code() == StatusCode::kStale) {
    ReportStartingOver(fetched, args.state);
    blocking = std::make_unique<client::BlockingSession>(state.url, options, transport);
    fetched = blocking->Fetch(budget, output->Handler());
  }
  client::Session& session = blocking->session();
  state.cursor = session.progress().packets;
  state.budget_bytes =
      fetched.ok() ? session.budget_bytes() : state.budget_bytes;
  state.container = session.Container();
  state.served_container = session.ServedContainer();
  MW_RETURN_IF_ERROR(client::SaveState(args.state, state));
  if (!fetched.ok()) return fetched.WithContext(state.url.ToString());
  return output->Finish(session, state.url.ToString(), args.state);
}

}  // namespace

void AddRefineCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RefineArgs>();
  CLI::App* cmd = app.add_subcommand("refine",
                                     "Pull the next packets of a mesh fetched "
                                     "with --state, and write the finer mesh");
  cmd->add_option("state", args->state,
                  "State file written by `meshwave fetch --state`")
      ->required();
  cmd->add_option("--more", args->more,
                  "Bytes to add to the budget (e.g. 64KiB); with a region (given, or the "
                  "state's last), bytes of the units it puts first")
      ->required();
  AddFetchOutputOptions(cmd, args->output,
                        "Output mesh (.ply, .obj, .glb, .gltf; default: STATE as .ply)",
                        /*out_required=*/false);
  AddRegionOptions(cmd, args->region);
  AddClientOptions(cmd, args->client);
  AddDecodeLimitOptions(cmd, args->limits);
  cmd->callback([args, &exit_code] {
    const Status s = Run(*args);
    if (!s.ok()) exit_code = Fail("refine", s);
  });
}

}  // namespace meshwave::cli
