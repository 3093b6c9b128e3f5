#include "run_to_completion.h"

#include <utility>

namespace meshwave::client {

Status StatusOf(std::exception_ptr e, Status status) {
  if (!e) return status;
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& ex) {
    return Status(StatusCode::kInternal, ex.what());
  } catch (...) {
    return Status(StatusCode::kInternal, "unknown exception");
  }
}

Status RunToCompletion(net::io_context& io, net::awaitable<Status> task) {
  Status result(StatusCode::kInternal, "the task did not finish");
  bool finished = false;
  net::co_spawn(io, std::move(task), [&](std::exception_ptr e, Status s) {
    result = StatusOf(e, std::move(s));
    finished = true;
  });
  io.restart();
  while (!finished && io.run_one() > 0) {
  }
  return result;
}

}  // namespace meshwave::client
