#include "region_fetch.h"
#include "meshwave/region_text.h"

#include <iostream>
#include <variant>

namespace meshwave::cli {

void AddRegionOptions(CLI::App* cmd, RegionRequestArgs& args) {
  cmd->add_option("--region", args.region,
                  "Refine this sphere first: x,y,z,r in the mesh's coordinates (a stream with "
                  "precincts; docs/API.md, Region requests)");
  cmd->add_option("--view", args.view,
                  "Refine what this camera sees first: ex,ey,ez,dx,dy,dz,fov,width,height "
                  "(position, direction, vertical field of view in degrees, screen pixels)");
  cmd->add_option("--screen-error", args.screen_error,
                  "With --view: pixels of projected error the view accepts (reserved)")
      ->check(CLI::PositiveNumber);
}

Result<std::optional<Region>> RegionFrom(const RegionRequestArgs& args) {
  if (!args.region.empty() && !args.view.empty()) {
    return InvalidArgument("give one of --region and --view");
  }
  if (args.screen_error > 0 && args.view.empty()) {
    return InvalidArgument("--screen-error goes with --view");
  }
  if (!args.given()) return std::optional<Region>();
  auto r = args.region.empty() ? ParseViewRegion(args.view) : ParseSphereRegion(args.region);
  if (!r.ok()) return InvalidArgument((args.region.empty() ? "--view: " : "--region: ") +
                                      r.status().message());
  if (args.screen_error > 0) {
    MW_ASSIGN_OR_RETURN(double px, CheckScreenError(args.screen_error));
    r->screen_error_px = px;
  }
  return std::optional<Region>(*std::move(r));
}

std::string RegionStateText(const std::optional<Region>& region) {
  if (!region) return "";
  if (std::holds_alternative<SphereRegion>(region->shape)) {
    return "sphere:" + FormatRegionShape(*region);
  }
  std::string out = "view:" + FormatRegionShape(*region);
  if (region->screen_error_px) out += "@" + FormatScreenError(*region->screen_error_px);
  return out;
}

Result<std::optional<Region>> RegionFromStateText(const std::string& text) {
  if (text.empty()) return std::optional<Region>();
  if (text.rfind("sphere:", 0) == 0) {
    MW_ASSIGN_OR_RETURN(Region r, ParseSphereRegion(text.substr(7)));
    return std::optional<Region>(r);
  }
  if (text.rfind("view:", 0) == 0) {
    const std::string rest = text.substr(5);
    const size_t at = rest.find('@');
    MW_ASSIGN_OR_RETURN(Region r, ParseViewRegion(rest.substr(0, at)));
    if (at != std::string::npos) {
      MW_ASSIGN_OR_RETURN(double px, ParseScreenError(rest.substr(at + 1)));
      r.screen_error_px = px;
    }
    return std::optional<Region>(r);
  }
  return ParseError("the state's region \"" + text.substr(0, 40) + "\" is not sphere: or view:");
}

Status RunRegionFetch(client::RegionSession& session, const client::MeshUrl& url,
                      const std::optional<Region>& region, std::optional<uint64_t> budget,
                      bool budget_counts_header, FetchOutput& output,
                      const std::string& state_path) {
  const Status fetched =
      session.FetchBlocking(region, budget, budget_counts_header, output.Handler());
  const client::Progress p = session.progress();
  if (!state_path.empty() && session.has_header() && (fetched.ok() || p.packets > 0)) {
    client::LocalState state;
    state.url = url;
    state.order = session.options().order;
    state.max_level = session.options().max_level;
    state.units = true;
    state.budget_bytes = p.bytes;
    state.container = session.Container();
    state.parts = session.Parts();
    state.held = session.HeldText();
    state.region = RegionStateText(region);
    const Status saved = client::SaveState(state_path, state);
    if (!fetched.ok() && saved.ok()) {
      std::cerr << "meshwave: kept the " << p.packets << " units received in " << state_path
                << "\n";
    }
    if (fetched.ok()) MW_RETURN_IF_ERROR(saved);
  }
  if (!fetched.ok()) return fetched.WithContext(url.ToString());
  const std::string counted =
      region ? std::string("units, ") +
                   (std::holds_alternative<SphereRegion>(region->shape) ? "region" : "view") +
                   " first"
             : std::string("units in ") + ProgressionName(session.options().order) + " order";
  return output.Finish(session.decoder(), p,
                       region ? "region" : ProgressionName(session.options().order), counted,
                       url.ToString(), state_path);
}

}  // namespace meshwave::cli
