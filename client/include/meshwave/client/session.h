// Session: fetches one mesh's stream from a server by cursor, feeds every
// packet to a ProgressiveDecoder (CRC and dependency checks) and reports
// after every refinement. It resumes a dropped transfer from its cursor with
// exponential backoff, and never asks for a packet it already holds.
#ifndef MESHWAVE_CLIENT_SESSION_H_
#define MESHWAVE_CLIENT_SESSION_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "meshwave/client/backoff.h"
#include "meshwave/client/budget.h"
#include "meshwave/client/transport.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"

namespace meshwave::client {

struct SessionOptions {
  Progression order = Progression::kQuality;
  int max_level = -1;  // -1: all levels
  RetryPolicy retry;
  // What the client accepts from a server, so that a hostile or broken one
  // cannot make it allocate at will: the container header's size (checked
  // on its length field, before the header is read) and the mesh the
  // header describes (DecoderOptions::max_faces, max_base_vertices; checked
  // before the decoder allocates).
  uint64_t max_header_bytes = kDefaultMaxHeaderBytes;
  DecoderOptions decoder;
};

// The state after a refinement.
struct Progress {
  size_t packets = 0;           // the cursor: packets of the order decoded
  size_t order_packets = 0;     // packets in the order
  uint64_t bytes = 0;           // size of the container holding them
  uint64_t received_bytes = 0;  // response bodies read by this session
  size_t packets_received = 0;  // packets this session received (not restored)
  int level = 0;  // complete levels (ProgressiveDecoder::CompleteLevels)
  int levels = 0;
  double estimated_psnr_db = 0;  // from the packet index; +inf when lossless
  int retries = 0;
  bool complete() const { return packets == order_packets; }
};

// Called on the session's executor once the header is known (the base mesh,
// 0 packets) and after every packet. The decoder gives the mesh on demand
// (decoder.Mesh(max_level)); do not keep the reference. Nothing is
// reconstructed unless the handler asks: Mesh() runs the whole inverse
// transform on this thread, and while it runs the next packets wait, so a
// handler that only shows progress should not call it every time.
using ProgressHandler =
    std::function<void(const Progress&, const ProgressiveDecoder&)>;

class Session {
 public:
  Session(std::unique_ptr<Transport> transport, const SessionOptions& options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Starts from packets received earlier: `container` must be a complete
  // container holding a prefix of the session's order (what Container()
  // gave). Safe on untrusted bytes; on error the session is left empty.
  Status Restore(std::string_view container, uint64_t budget_bytes);

  // Fetches until `budget` is reached in the session's order (counted from
  // the start of the stream: a byte budget counts the whole container).
  // Coroutine on the transport's executor. Errors: the transport's final
  // errors at once, kIoError after retry.max_attempts tries without
  // progress, kParseError for a corrupt or unexpected response.
  net::awaitable<Status> Fetch(Budget budget, ProgressHandler on_progress);

  // Fetch without coroutines: starts it on the transport's executor and
  // returns at once; `done` runs there at the end. The session must outlive
  // the fetch.
  void AsyncFetch(Budget budget, ProgressHandler on_progress,
                  std::function<void(Status)> done);

  bool has_header() const;
  const ProgressiveDecoder* decoder() const;  // null before the header
  const SessionOptions& options() const;
  Progress progress() const;
  // Container bytes asked for so far: the largest byte budget fetched, or
  // the container size reached by other budgets.
  uint64_t budget_bytes() const;
  // The packets held as a valid container ("meshwave decode" reads it);
  // empty before the header.
  std::string Container() const;
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

#endif  // MESHWAVE_CLIENT_SESSION_H_
