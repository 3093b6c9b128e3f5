#include "server.h"

#include <spdlog/spdlog.h>

#include <condition_variable>
#include <csignal>
#include <thread>
#include <vector>

#include "core/durable_file.h"
#include "catalog_watcher.h"
#include "ingest.h"
#include "listener.h"
#include "server_config.h"
#include "server_context.h"
#include "worker_process.h"

namespace meshwave::server {

namespace {

// `reencode_on_start`: the re-encode runs in a worker process on the
// ingest thread (so it waits for, and is waited for by, uploads), its
// report in the server's log.
void StartBackgroundReencode(ServerContext& ctx) {
  net::post(ctx.ingest_pool(), [&ctx] {
    std::vector<std::string> args = {"reencode", "--catalog", ctx.catalog_location(),
                                     "--threads", std::to_string(ctx.config().threads())};
    if (!ctx.store_location().empty()) {
      args.insert(args.end(), {"--store", ctx.store_location().string()});
    }
    WorkerOptions options;
    options.nice = static_cast<int>(ctx.config().ingest_nice());
    options.memory_limit_bytes = ctx.config().ingest_memory_limit_bytes();
    spdlog::info("re-encoding out-of-date meshes in the background");
    auto run = RunWorker(args, "", options);
    if (!run.ok()) {
      spdlog::error("background reencode: {}", run.status().ToString());
      return;
    }
    for (const std::string* text : {&run->out, &run->err}) {
      size_t i = 0;
      while (i < text->size()) {
        const size_t end = std::min(text->find('\n', i), text->size());
        if (end > i) spdlog::info("background {}", std::string_view(*text).substr(i, end - i));
        i = end + 1;
      }
    }
    if (run->exit_code != 0) spdlog::error("background reencode {}", DescribeExit(run->exit_code));
  });
}

}  // namespace

Status RunServer(const ServeOptions& options) {
  const proto::ServerConfig& config = options.config;
  MW_ASSIGN_OR_RETURN(std::unique_ptr<Catalog> catalog,
                      Catalog::Open(options.catalog, options.store));
  MW_ASSIGN_OR_RETURN(CleanupReport cleanup,
                      RemoveOrphans(*catalog, config.retired_container_seconds()));
  if (cleanup.orphan_files + cleanup.temp_files + cleanup.orphan_originals > 0) {
    spdlog::warn("catalog {}: removed {} orphan containers, {} orphan original files and {} "
                 "temporary files",
                 catalog->Describe(), cleanup.orphan_files, cleanup.orphan_originals,
                 cleanup.temp_files);
  }
  MW_ASSIGN_OR_RETURN(ListenAddress address, ParseListenAddress(config.listen()));
  beast::error_code ec;
  const auto ip = net::ip::make_address(address.host, ec);
  if (ec) return InvalidArgument("listen address '" + address.host + "': " + ec.message());

  ServerContext ctx(config, std::move(catalog));
  ctx.set_catalog_location(options.catalog, options.store);
  CatalogWatcher watcher(ctx.catalog(), ctx.cache(), ctx.response_cache(),
                         std::chrono::milliseconds(config.catalog_poll_milliseconds()));
  const int threads = static_cast<int>(config.threads());
  // One io_context per thread (each run by its thread alone: no strands,
  // no lock shared between threads on the way of a request), or one
  // shared by all threads (shared_io_context, the layout before issue 19).
  const bool shared = config.shared_io_context();
  std::vector<std::unique_ptr<net::io_context>> contexts;
  std::vector<net::io_context*> context_ptrs;
  for (int i = 0; i < (shared ? 1 : threads); ++i) {
    contexts.push_back(std::make_unique<net::io_context>(shared ? threads : 1));
    context_ptrs.push_back(contexts.back().get());
  }
  net::io_context& main_ioc = *contexts.front();
  MW_ASSIGN_OR_RETURN(auto listener, Listener::Create(context_ptrs, shared,
                                                      tcp::endpoint(ip, address.port), ctx));
  spdlog::info("meshwave-server listening on {}:{} ({} threads, {}, catalog {})", address.host,
               listener->port(), threads,
               shared ? "one shared io_context" : "an io_context per thread",
               ctx.catalog().Describe());
  if (!options.port_file.empty()) {
    MW_RETURN_IF_ERROR(WriteFileDurably(std::filesystem::absolute(options.port_file),
                                        std::to_string(listener->port()) + "\n"));
  }
  if (config.reencode_on_start()) StartBackgroundReencode(ctx);
  // Each io_context runs until the stop, even while no connection is on it.
  std::vector<net::executor_work_guard<net::io_context::executor_type>> guards;
  for (auto& c : contexts) guards.push_back(net::make_work_guard(*c));
  listener->Run();

  // Stop on a signal: no new connections, sessions finish what they do.
  std::mutex mutex;
  std::condition_variable cv;
  bool stop_requested = false, finished = false;
  net::signal_set signals(main_ioc, SIGINT, SIGTERM);
  signals.async_wait([&](beast::error_code wait_ec, int signal) {
    if (wait_ec) return;
    spdlog::info("signal {}: stopping", signal);
    listener->Stop();
    ctx.ShutdownSessions();
    // Each io_context returns once its sessions have ended.
    for (auto& g : guards) g.reset();
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
      for (auto& c : contexts) c->stop();
    }
  });

  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) {
    net::io_context& ioc = shared ? main_ioc : *contexts[static_cast<size_t>(i)];
    pool.emplace_back([&ioc] { ioc.run(); });
  }
  main_ioc.run();
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
