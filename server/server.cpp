#include "server.h"

#include <spdlog/spdlog.h>

#include <condition_variable>
#include <csignal>
#include <thread>
#include <vector>

#include "core/durable_file.h"
#include "ingest.h"
#include "listener.h"
#include "server_config.h"
#include "server_context.h"

namespace meshwave::server {

Status RunServer(const ServeOptions& options) {
  const proto::ServerConfig& config = options.config;
  MW_ASSIGN_OR_RETURN(std::unique_ptr<Catalog> catalog,
                      Catalog::Open(options.catalog, options.store));
  MW_ASSIGN_OR_RETURN(CleanupReport cleanup, RemoveOrphans(*catalog));
  if (cleanup.orphan_files + cleanup.temp_files > 0) {
    spdlog::warn("catalog {}: removed {} orphan and {} temporary files", catalog->Describe(),
                 cleanup.orphan_files, cleanup.temp_files);
  }
  MW_ASSIGN_OR_RETURN(ListenAddress address, ParseListenAddress(config.listen()));
  beast::error_code ec;
  const auto ip = net::ip::make_address(address.host, ec);
  if (ec) return InvalidArgument("listen address '" + address.host + "': " + ec.message());

  ServerContext ctx(config, std::move(catalog));
  const int threads = static_cast<int>(config.threads());
  net::io_context ioc(threads);
  MW_ASSIGN_OR_RETURN(auto listener, Listener::Create(ioc, tcp::endpoint(ip, address.port), ctx));
  spdlog::info("meshwave-server listening on {}:{} ({} threads, catalog {})", address.host,
               listener->port(), threads, ctx.catalog().Describe());
  if (!options.port_file.empty()) {
    MW_RETURN_IF_ERROR(WriteFileDurably(std::filesystem::absolute(options.port_file),
                                        std::to_string(listener->port()) + "\n"));
  }
  listener->Run();

  // Stop on a signal: no new connections, sessions finish what they do.
  std::mutex mutex;
  std::condition_variable cv;
  bool stop_requested = false, finished = false;
  net::signal_set signals(ioc, SIGINT, SIGTERM);
  signals.async_wait([&](beast::error_code wait_ec, int signal) {
    if (wait_ec) return;
    spdlog::info("signal {}: stopping", signal);
    listener->Stop();
    ctx.ShutdownSessions();
    std::lock_guard lock(mutex);
    stop_requested = true;
    cv.notify_all();
  });
  // Cuts the grace period short of a client that never finishes reading.
  std::thread watchdog([&] {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return stop_requested || finished; });
    if (finished) return;
    if (!cv.wait_for(lock, std::chrono::seconds(config.shutdown_grace_seconds()),
                     [&] { return finished; })) {
      spdlog::warn("grace period over: closing the remaining connections");
      ioc.stop();
    }
  });

  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back([&ioc] { ioc.run(); });
  ioc.run();
  for (auto& t : pool) t.join();
  ctx.ingest_pool().join();
  {
    std::lock_guard lock(mutex);
    finished = true;
    cv.notify_all();
  }
  watchdog.join();
  spdlog::info("meshwave-server stopped");
  return Status::Ok();
}

}  // namespace meshwave::server
