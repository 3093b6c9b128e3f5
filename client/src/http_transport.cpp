// The HTTP transport: /header, /packets/{k} and /stream of one mesh.
#include <charconv>

#include "co_status.h"
#include "header_limit.h"
#include "http_client.h"
#include "meshwave/client/transport.h"
#include "meshwave/region_text.h"
#include "meshwave/stream_units.h"

namespace meshwave::client {
namespace {

constexpr uint64_t kPacketLimit = uint64_t{1} << 30;

Result<uint64_t> HeaderNumber(const http::response_header<>& head,
                              std::string_view name) {
  const auto it = head.find(name);
  if (it == head.end()) {
    return ParseError("the response has no " + std::string(name) + " header");
  }
  const std::string_view v = it->value();
  uint64_t n = 0;
  auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || ec != std::errc() || ptr != v.data() + v.size()) {
    return ParseError(std::string(name) + " \"" + std::string(v) +
                      "\" is not a number");
  }
  return n;
}

Result<StreamHead> ParseStreamHead(const http::response_header<>& head) {
  StreamHead h;
  MW_ASSIGN_OR_RETURN(uint64_t packets,
                      HeaderNumber(head, "X-Meshwave-Packets"));
  MW_ASSIGN_OR_RETURN(uint64_t next,
                      HeaderNumber(head, "X-Meshwave-Next-Cursor"));
  h.packets = static_cast<size_t>(packets);
  h.next_cursor = static_cast<size_t>(next);
  const auto complete = head.find("X-Meshwave-Complete");
  h.complete = complete != head.end() && complete->value() == "true";
  if (head.find(http::field::content_length) != head.end()) {
    MW_ASSIGN_OR_RETURN(uint64_t length, HeaderNumber(head, "Content-Length"));
    h.content_length = length;
  }
  return h;
}

class HttpTransport final : public Transport {
 public:
  HttpTransport(net::any_io_executor executor, const MeshUrl& url,
                const TransportOptions& options)
      : url_(url), client_(std::move(executor), url.server, options) {}

  net::any_io_executor executor() override { return client_.executor(); }

  net::awaitable<Result<std::string>> GetHeader(
      uint64_t max_header_bytes) override {
    // Refused from Content-Length when the server sends one, else as soon
    // as the bytes pass the limit: never more than the limit buffered.
    std::string body;
    Status s = co_await client_.Get(
        url_.Path() + "/header", "application/x-protobuf",
        [&](const http::response_header<>& head) -> Status {
          if (head.find(http::field::content_length) == head.end())
            return Status::Ok();
          auto length = HeaderNumber(head, "Content-Length");
          if (!length.ok()) return length.status();
          return CheckHeaderLength(*length, max_header_bytes);
        },
        [&](std::string_view bytes) -> Status {
          MW_RETURN_IF_ERROR(
              CheckHeaderLength(body.size() + bytes.size(), max_header_bytes));
          body.append(bytes);
          return Status::Ok();
        });
    if (!s.ok()) co_return s;
    co_return body;
  }

  net::awaitable<Result<std::string>> GetPacket(uint32_t id) override {
    co_return co_await client_.GetBody(
        url_.Path() + "/packets/" + std::to_string(id), "", kPacketLimit);
  }

  net::awaitable<Status> Stream(const StreamRequest& request,
                                StreamSink& sink) override {
    if (request.header_held && request.from == 0) {
      co_return InvalidArgument(
          "HTTP cannot stream payloads from cursor 0 without the header");
    }
    std::string target =
        url_.Path() + "/stream?order=" + ProgressionName(request.order);
    if (request.max_level >= 0)
      target += "&max_level=" + std::to_string(request.max_level);
    if (request.from > 0) target += "&from=" + std::to_string(request.from);
    if (request.budget) target += "&budget=" + std::to_string(*request.budget);
    co_return co_await client_.Get(
        target, "",
        [&](const http::response_header<>& head) -> Status {
          auto h = ParseStreamHead(head);
          if (!h.ok()) return h.status().WithContext("GET " + target);
          return sink.OnHead(*h);
        },
        [&](std::string_view bytes) { return sink.OnBytes(bytes); });
  }

  net::awaitable<Status> StreamUnits(const UnitStreamRequest& request,
                                     UnitSink& sink) override {
    std::string target = url_.Path() + "/stream?";
    if (request.region) {
      const bool sphere = std::holds_alternative<SphereRegion>(request.region->shape);
      target += (sphere ? "region=" : "view=") + FormatRegionShape(*request.region);
      if (request.region->screen_error_px) {
        target += "&screen_error=" + FormatScreenError(*request.region->screen_error_px);
      }
    } else {
      target += std::string("order=") + ProgressionName(request.order);
    }
    // Always named, even empty: the request is then a region request.
    target += "&held=" + request.held;
    if (request.max_level >= 0) target += "&max_level=" + std::to_string(request.max_level);
    if (request.budget) target += "&budget=" + std::to_string(*request.budget);
    UnitRecordReader reader(request.max_payload, [&](StreamUnit u, std::string_view payload) {
      return sink.OnUnit(u, payload);
    });
    Status s = co_await client_.Get(
        target, "",
        [&](const http::response_header<>& head) -> Status {
          auto units = HeaderNumber(head, "X-Meshwave-Units");
          return units.ok() ? Status::Ok() : units.status().WithContext("GET " + target);
        },
        [&](std::string_view bytes) { return reader.Feed(bytes); });
    if (s.ok() && !reader.at_boundary()) {
      s = IoError("GET " + target + ": the body ended inside a unit");
    }
    co_return s;
  }

  void Close() override { client_.Close(); }

 private:
  MeshUrl url_;
  HttpClient client_;
};

}  // namespace

std::unique_ptr<Transport> MakeTransport(net::any_io_executor executor,
                                         const MeshUrl& url,
                                         const TransportOptions& options) {
  if (url.server.websocket) {
    return MakeWebSocketTransport(std::move(executor), url, options);
  }
  return MakeHttpTransport(std::move(executor), url, options);
}

std::unique_ptr<Transport> MakeHttpTransport(net::any_io_executor executor,
                                             const MeshUrl& url,
                                             const TransportOptions& options) {
  return std::make_unique<HttpTransport>(std::move(executor), url, options);
}

}  // namespace meshwave::client
