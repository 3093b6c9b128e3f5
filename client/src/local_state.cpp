#include "meshwave/client/local_state.h"

#include <fstream>
#include <sstream>

#include "client_state.pb.h"
#include "core/durable_file.h"
#include "meshwave/container.h"
#include "meshwave/mesh_id.h"
#include "meshwave/stream_limits.h"

namespace meshwave::client {
namespace {

constexpr uint32_t kStateVersion = 1;
constexpr uintmax_t kMaxStateBytes = uintmax_t{1} << 32;

Result<std::string> ReadAll(const std::filesystem::path& path) {
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return IoError("cannot read " + path.string() + ": " + ec.message());
  if (size > kMaxStateBytes)
    return ParseError(path.string() + ": too large for a state file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  if (!in && !in.eof()) return IoError("cannot read " + path.string());
  return out.str();
}

}  // namespace

std::filesystem::path SidecarPath(const std::filesystem::path& file) {
  return file.string() + ".session";
}

std::string SessionBytes(const LocalState& state) {
  proto::ClientState meta;
  meta.set_version(kStateVersion);
  meta.set_mesh_url(state.url.ToString());
  meta.set_order(ProgressionName(state.order));
  meta.set_max_level(state.max_level);
  meta.set_cursor(state.cursor);
  meta.set_budget_bytes(state.budget_bytes);
  meta.set_units(state.units);
  meta.set_parts(state.parts);
  meta.set_held(state.held);
  meta.set_region(state.region);
  meta.set_served_container(state.served_container);
  return meta.SerializeAsString();
}

Status SaveState(const std::filesystem::path& file, const LocalState& state) {
  MW_RETURN_IF_ERROR(WriteFileDurably(file, state.container));
  return WriteFileDurably(SidecarPath(file), SessionBytes(state));
}

Result<LocalState> LoadState(const std::filesystem::path& file) {
  MW_ASSIGN_OR_RETURN(std::string meta_bytes, ReadAll(SidecarPath(file)));
  MW_ASSIGN_OR_RETURN(std::string container, ReadAll(file));
  return ParseState(meta_bytes, std::move(container), file);
}

Result<LocalState> ParseState(std::string_view session, std::string container,
                              const std::filesystem::path& file) {
  const std::filesystem::path sidecar = SidecarPath(file);
  auto refuse = [&](const std::filesystem::path& which,
                    const std::string& why) {
    return ParseError("state " + which.string() + ": " + why);
  };
  proto::ClientState meta;
  if (!meta.ParseFromArray(session.data(), static_cast<int>(session.size())))
    return refuse(sidecar, "does not parse");
  if (meta.version() != kStateVersion) {
    return refuse(sidecar, "version " + std::to_string(meta.version()) +
                               " (expected " + std::to_string(kStateVersion) +
                               ")");
  }
  LocalState state;
  auto url = ParseMeshUrl(meta.mesh_url());
  if (!url.ok()) return refuse(sidecar, url.status().message());
  state.url = std::move(*url);
  auto order = ParseProgression(meta.order());
  if (!order.ok()) return refuse(sidecar, order.status().message());
  state.order = *order;
  if (meta.max_level() < -1 || meta.max_level() > kMaxStreamLevels) {
    return refuse(sidecar, "max_level " + std::to_string(meta.max_level()) +
                               " out of range");
  }
  state.max_level = meta.max_level();
  state.budget_bytes = meta.budget_bytes();
  if (!meta.served_container().empty() && !IsValidContainerDigest(meta.served_container())) {
    return refuse(sidecar, "served_container is not a container digest");
  }
  state.served_container = meta.served_container();

  state.container = std::move(container);
  auto parsed = ParseContainer(state.container);
  if (!parsed.ok()) return refuse(file, parsed.status().message());
  if (meta.units()) {
    state.units = true;
    state.parts = meta.parts();
    state.held = meta.held();
    state.region = meta.region();
    return state;
  }
  if (meta.cursor() != parsed->ids.size()) {
    return refuse(file, "holds " + std::to_string(parsed->ids.size()) +
                            " packets but " + sidecar.string() + " says " +
                            std::to_string(meta.cursor()) +
                            " (the two files do not belong together)");
  }
  state.cursor = parsed->ids.size();
  return state;
}

}  // namespace meshwave::client
