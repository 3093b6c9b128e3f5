// What a client keeps between runs: FILE, a valid partial container of the
// packets received (`meshwave decode FILE` reads it), and FILE.session, a
// ClientState protobuf naming the server URL, mesh, order, level limit,
// cursor and byte budget. Both are written atomically (temporary file,
// fsync, rename); the container format is not changed.
#ifndef MESHWAVE_CLIENT_LOCAL_STATE_H_
#define MESHWAVE_CLIENT_LOCAL_STATE_H_

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "meshwave/client/url.h"
#include "meshwave/progression.h"
#include "meshwave/status.h"

namespace meshwave::client {

struct LocalState {
  MeshUrl url;
  Progression order = Progression::kQuality;
  int max_level = -1;
  size_t cursor = 0;          // packets of the order in `container`
  uint64_t budget_bytes = 0;  // container bytes asked for so far
  std::string container;      // holds exactly order[0 .. cursor)
  // A session of units (RegionSession): `container` holds the packets held
  // whole, `parts` unit records of the other units held; `held` is the
  // held bitmap's text, `region` the last region's (FormatRegionShape, a
  // view prefixed "view:"), for the record. `cursor` is not used.
  bool units = false;
  std::string parts;
  std::string held;
  std::string region;
  // The container the server served them from (Session::ServedContainer),
  // empty when it did not say: a refine names it, and starts over when the
  // mesh has been re-encoded since.
  std::string served_container;
};

// FILE.session.
std::filesystem::path SidecarPath(const std::filesystem::path& file);

// The bytes of FILE.session for `state` (a ClientState protobuf).
std::string SessionBytes(const LocalState& state);

// Writes the container, then the sidecar. IoError naming the path.
Status SaveState(const std::filesystem::path& file, const LocalState& state);

// Reads and checks both files; safe on untrusted bytes. Refuses (kParseError,
// naming the file) a sidecar that does not parse or names an unknown
// version, URL or order, a container that does not parse or is cut short,
// and a cursor that differs from the container's packet count (a session of
// packets). Whether a session of units' parts decode and match `held` is
// checked when a RegionSession restores them. Whether the
// packets are the order's prefix and pass their CRCs is checked when a
// Session restores the container.
Result<LocalState> LoadState(const std::filesystem::path& file);

// LoadState's checks on bytes already read: `session` the sidecar's,
// `container` FILE's; `file` names them in messages. Safe on untrusted
// bytes (fuzzed: tests/fuzz/local_state_fuzz.cpp).
Result<LocalState> ParseState(std::string_view session, std::string container,
                              const std::filesystem::path& file);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_LOCAL_STATE_H_
