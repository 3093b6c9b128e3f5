// RegionSession: fetches one mesh's units region first (docs/API.md,
// "Region requests"). Each fetch names a region, a view or a uniform order
// and a byte budget, and continues from everything held, so that nothing
// is received twice across regions; every unit goes to a
// ProgressiveDecoder as it arrives. A dropped transfer is asked again for
// what is still missing, with exponential backoff.
#ifndef MESHWAVE_CLIENT_REGION_SESSION_H_
#define MESHWAVE_CLIENT_REGION_SESSION_H_

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/client/session.h"
#include "meshwave/client/transport.h"
#include "meshwave/client/url.h"
#include "meshwave/region.h"

namespace meshwave::client {

class RegionSession {
 public:
  RegionSession(std::unique_ptr<Transport> transport, const SessionOptions& options);
  // With its own io_context and the transport the URL's scheme names: for
  // FetchBlocking.
  RegionSession(const MeshUrl& url, const SessionOptions& options,
                const TransportOptions& transport_options);
  ~RegionSession();
  RegionSession(const RegionSession&) = delete;
  RegionSession& operator=(const RegionSession&) = delete;

  // Fetches the header if it is not held, then the units `region` puts
  // first (absent: the options' uniform order) until `budget` bytes of
  // units more (absent: everything left); with `budget_counts_header` the
  // budget pays for the header's container size first (kInvalidArgument
  // when it cannot). Progress::packets counts the units held,
  // order_packets the stream's, bytes the header's container size plus the
  // payloads held. Errors as Session::Fetch's.
  net::awaitable<Status> Fetch(std::optional<Region> region, std::optional<uint64_t> budget,
                               bool budget_counts_header, ProgressHandler on_progress);
  // Fetch on the session's own io_context (the URL constructor), run on
  // the calling thread.
  Status FetchBlocking(std::optional<Region> region, std::optional<uint64_t> budget,
                       bool budget_counts_header, const ProgressHandler& on_progress = {});

  // Starts from what Container() and Parts() gave: the header and the
  // packets held whole (a container), and unit records of the rest. Safe on
  // untrusted bytes; on error the session is left empty.
  Status Restore(std::string_view container, std::string_view parts);

  bool has_header() const;
  const ProgressiveDecoder* decoder() const;  // null before the header
  const SessionOptions& options() const;
  Progress progress() const;
  // Container size of the header alone (0 before it): what a byte budget
  // that counts the header spends on it.
  uint64_t header_bytes() const;
  // The units held, as a held bitmap's text (docs/API.md).
  std::string HeldText() const;
  // The packets held whole whose dependencies are too, as a valid
  // container (`meshwave decode` reads it); empty before the header.
  std::string Container() const;
  // Unit records (stream_units.h) of every other unit held, in an order
  // that decodes after the container.
  std::string Parts() const;
  // The container (SHA-256, 64 hex digits) what is held came from, empty
  // when the server did not say (Transport::served_container); keep it with
  // a saved state and give it back to PinContainer after Restore: a mesh
  // re-encoded since then is refused with kStale, never mixed.
  const std::string& ServedContainer() const;
  void PinContainer(std::string digest);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_REGION_SESSION_H_
