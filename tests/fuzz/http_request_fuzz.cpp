// Fuzz target: what the server does with an untrusted HTTP request before
// and while routing it: Beast's request parser with the server's header and
// body limits, InspectHeader, and HandleRequest (ParseRequestTarget, mesh
// ids, ParseStreamQuery, Range, If-None-Match, Accept) against a catalog
// holding the fixture container. The input is the raw request bytes.
// No upload token is configured, so no upload or deletion may succeed: the
// catalog never changes between inputs (checked).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include "api_router.h"
#include "fuzz_fixture_testonly.h"
#include "ingest.h"
#include "server_config.h"

using namespace meshwave;
using namespace meshwave::server;

namespace {

std::filesystem::path g_dir;

ServerContext& Context() {
  static ServerContext* ctx = [] {
    char dir[] = "/tmp/meshwave-fuzz-XXXXXX";
    fuzz::Require(::mkdtemp(dir) != nullptr, "mkdtemp");
    g_dir = dir;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(g_dir, ec);
    });
    auto catalog = Catalog::Open(g_dir);
    fuzz::Require(catalog.ok(), "catalog opens");
    fuzz::Require(IngestContainer(**catalog, fuzz::GetFixture().bytes, "octahedron", "fuzz").ok(),
                  "fixture ingests");
    ::unsetenv("MESHWAVE_UPLOAD_TOKEN");
    proto::ServerConfig config;
    fuzz::Require(FinishServerConfig(config).ok(), "default config");
    return new ServerContext(std::move(config), std::move(*catalog));
  }();
  return *ctx;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ServerContext& ctx = Context();
  http::request_parser<http::string_body> parser;
  parser.header_limit(ctx.config().header_limit_bytes());
  parser.body_limit(ctx.config().body_limit_bytes());
  parser.eager(true);
  beast::error_code ec;
  parser.put(net::buffer(data, size), ec);
  if (ec || !parser.is_header_done()) return 0;
  const HeaderDecision d = InspectHeader(ctx, parser.get().base());
  if (d.reject) {
    fuzz::Require(d.reject->result_int() >= 400, "a rejection is an error status");
    return 0;
  }
  // Routes that exist for uploads and deletions are refused at the header
  // (no token); a POST or DELETE elsewhere reaches HandleRequest's 404/405.
  const bool mutating = parser.get().method() == http::verb::post ||
                        parser.get().method() == http::verb::delete_;
  fuzz::Require(!d.upload, "without a token no upload is accepted at the header");
  if (!parser.is_done()) return 0;
  std::optional<Response> response;
  HandleRequest(ctx, parser.release(), [&](Response r) { response = std::move(r); });
  fuzz::Require(response.has_value(), "requests other than uploads are answered on the calling thread");
  fuzz::Require(response->result_int() >= 200 && response->result_int() < 500,
                "an untrusted request gets a 2xx, 3xx or 4xx, never a 5xx");
  if (mutating) {
    fuzz::Require(response->result_int() >= 400, "without a token no upload or deletion succeeds");
    const auto entries = ctx.catalog().Count();
    fuzz::Require(entries.ok() && *entries == 1, "the catalog still holds the fixture alone");
  }
  return 0;
}
