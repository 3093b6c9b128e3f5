// The client's one blocking run: a coroutine spawned on an io_context and
// run from the calling thread until it finishes. BlockingSession,
// RegionSession::FetchBlocking and ListCatalog use it.
#ifndef MESHWAVE_CLIENT_RUN_TO_COMPLETION_H_
#define MESHWAVE_CLIENT_RUN_TO_COMPLETION_H_

#include <exception>

#include "meshwave/status.h"
#include "net.h"

namespace meshwave::client {

// What an exception escaping a coroutine becomes: kInternal with its text
// (only allocation failures and bugs throw). `status` when there is none.
Status StatusOf(std::exception_ptr e, Status status);

// Runs `task` on `io` from the calling thread until it finishes, not until
// the io_context runs dry: a WebSocket kept open for the next fetch has its
// idle timer pending. `io` may have run before (it is restarted).
Status RunToCompletion(net::io_context& io, net::awaitable<Status> task);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_RUN_TO_COMPLETION_H_
