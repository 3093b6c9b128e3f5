#include "meshwave/client/catalog.h"

#include "http_client.h"
#include "run_to_completion.h"

namespace meshwave::client {
namespace {

constexpr uint64_t kPageLimit = 1000;  // the server's maximum page
constexpr uint64_t kListBytesLimit = uint64_t{1} << 26;

net::awaitable<Status> ListAll(HttpClient& client, proto::MeshList& all) {
  for (uint64_t offset = 0;;) {
    auto body = co_await client.GetBody(
        "/v1/meshes?limit=" + std::to_string(kPageLimit) +
            "&offset=" + std::to_string(offset),
        "application/x-protobuf", kListBytesLimit);
    if (!body.ok()) co_return body.status();
    proto::MeshList page;
    if (!page.ParseFromString(*body))
      co_return ParseError("the catalog listing does not parse");
    for (auto& m : *page.mutable_meshes()) *all.add_meshes() = std::move(m);
    all.set_total(page.total());
    offset += static_cast<uint64_t>(page.meshes_size());
    if (page.meshes_size() == 0 || offset >= page.total()) break;
  }
  all.set_limit(static_cast<uint64_t>(all.meshes_size()));
  co_return Status::Ok();
}

}  // namespace

Result<proto::MeshList> ListCatalog(const ServerUrl& server,
                                    const TransportOptions& options) {
  net::io_context io(1);
  proto::MeshList list;
  HttpClient client(io.get_executor(), server, options);
  const Status status = RunToCompletion(io, ListAll(client, list));
  if (!status.ok()) return status;
  return list;
}

}  // namespace meshwave::client
