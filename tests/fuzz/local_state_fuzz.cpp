// Fuzz target: the client's reading of its saved state (LoadState's checks,
// ParseState): FILE.session, a ClientState protobuf, and FILE, a container.
// Input: a 2-byte little-endian length, that many bytes of sidecar, then
// the container. A state that is accepted must hold what LoadState
// promises (a valid URL and order, max_level in range, for a session of
// packets a cursor equal to the container's packet count), and must come
// back identical when written as SaveState writes it and read again.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "meshwave/client/local_state.h"
#include "meshwave/container.h"

using namespace meshwave;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const size_t n =
      std::min<size_t>(data[0] | static_cast<size_t>(data[1]) << 8, size - 2);
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 2,
                               size - 2);
  const std::string_view session = bytes.substr(0, n);
  const std::string container(bytes.substr(n));
  auto state = client::ParseState(session, container, "fuzz.mwv");
  if (!state.ok()) {
    fuzz::Require(!state.status().message().empty(), "a refusal says why");
    fuzz::Require(state.status().code() == StatusCode::kParseError,
                  "bad bytes are a parse error");
    return 0;
  }
  fuzz::Require(state->max_level >= -1 && state->max_level <= 12,
                "max_level in range");
  auto parsed = ParseContainer(state->container);
  fuzz::Require(parsed.ok(), "the container parses");
  fuzz::Require(state->units || parsed->ids.size() == state->cursor,
                "the cursor counts the container's packets");
  fuzz::Require(client::ParseMeshUrl(state->url.ToString()).ok(),
                "the URL reads back");
  auto again = client::ParseState(client::SessionBytes(*state),
                                  state->container, "fuzz.mwv");
  fuzz::Require(again.ok(), "a state written back reads again");
  fuzz::Require(again->url.ToString() == state->url.ToString() &&
                    again->order == state->order &&
                    again->max_level == state->max_level &&
                    again->cursor == state->cursor &&
                    again->budget_bytes == state->budget_bytes &&
                    again->units == state->units && again->parts == state->parts &&
                    again->held == state->held && again->region == state->region,
                "a state survives being written back");
  return 0;
}
