// `meshwave fetch --region/--view` and `meshwave refine` of a session of
// units (docs/API.md, "Region requests"): the options, and a
// RegionSession's fetch written out like any fetch, its state kept.
#ifndef MESHWAVE_TOOLS_REGION_FETCH_H_
#define MESHWAVE_TOOLS_REGION_FETCH_H_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "fetch_output.h"
#include "meshwave/client/local_state.h"
#include "meshwave/client/region_session.h"
#include "meshwave/region.h"
#include "meshwave/status.h"

namespace meshwave::cli {

struct RegionRequestArgs {
  std::string region, view;
  double screen_error = 0;  // 0: none
  bool given() const { return !region.empty() || !view.empty(); }
};

// Registers --region, --view and --screen-error.
void AddRegionOptions(CLI::App* cmd, RegionRequestArgs& args);
// The region asked for, nullopt when none; kInvalidArgument for both at
// once, --screen-error without --view, and text that does not parse.
Result<std::optional<Region>> RegionFrom(const RegionRequestArgs& args);

// The region as the state file keeps it ("sphere:TEXT", "view:TEXT" or
// "view:TEXT@PX"), and back.
std::string RegionStateText(const std::optional<Region>& region);
Result<std::optional<Region>> RegionFromStateText(const std::string& text);

// Fetches `region` first (nullopt: the session's order) within `budget`,
// writes the mesh and, with a state path, the session's state (also after
// a failed fetch that received something); `budget_counts_header` as
// RegionSession::Fetch's.
Status RunRegionFetch(client::RegionSession& session, const client::MeshUrl& url,
                      const std::optional<Region>& region, std::optional<uint64_t> budget,
                      bool budget_counts_header, FetchOutput& output,
                      const std::string& state_path);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_REGION_FETCH_H_
