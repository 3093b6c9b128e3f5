// The WebSocket transport: GET /v1/ws of the server, the messages of
// proto/websocket.proto (docs/API.md, WebSocket).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#pragma GCC diagnostic pop

#include "co_status.h"
#include "meshwave/client/transport.h"
#include "meshwave/mesh_id.h"
#include "meshwave/region_text.h"
#include "net.h"
#include "server_connection.h"
#include "websocket.pb.h"
#include "ws_server_messages.h"

namespace meshwave::client {
namespace {

namespace websocket = beast::websocket;

// The largest packet the HTTP transport accepts, plus the message framing.
constexpr uint64_t kMessageLimit = (uint64_t{1} << 30) + 1024;
// "The rest of the order" in a refine (the server's largest budget).
constexpr uint64_t kWholeOrder = uint64_t{1} << 50;

// Collects the header of a header-only start.
class HeaderSink final : public StreamSink {
 public:
  Status OnHead(const StreamHead&) override { return Status::Ok(); }
  Status OnBytes(std::string_view) override {
    return ParseError("bytes where messages were expected");
  }
  Status OnHeaderMessage(std::string_view header) override {
    header_ = std::string(header);
    return Status::Ok();
  }
  Status OnPacketMessage(size_t, uint32_t, std::string_view) override {
    return ParseError("a packet after a request for the header alone");
  }
  std::string& header() { return header_; }

 private:
  std::string header_;
};

class WebSocketTransport final : public Transport {
 public:
  WebSocketTransport(net::any_io_executor executor, const MeshUrl& url,
                     const TransportOptions& options)
      : executor_(std::move(executor)), url_(url), options_(options) {}

  net::any_io_executor executor() override { return executor_; }

  net::awaitable<Result<std::string>> GetHeader(
      uint64_t max_header_bytes) override {
    StreamRequest request;  // the server's defaults: quality, all levels
    request.max_header_bytes = max_header_bytes;
    proto::ClientMessage m;
    auto* start = m.mutable_start();
    start->set_mesh_id(url_.mesh_id);
    start->set_header_only(true);
    start->set_container(pinned_);
    start->set_rate(options_.pace_bytes_per_second);
    HeaderSink sink;
    Status s = co_await Request(m, request, sink);
    if (!s.ok()) co_return s;
    if (sink.header().empty()) co_return ParseError("no stream header came");
    co_return std::move(sink.header());
  }

  net::awaitable<Result<std::string>> GetPacket(uint32_t /*id*/) override {
    // Never asked: CanStreamPayloadsFromStart.
    co_return Status(StatusCode::kUnsupported,
                     "the WebSocket transport streams packets by cursor");
  }

  net::awaitable<Status> Stream(const StreamRequest& request,
                                StreamSink& sink) override {
    co_return co_await Request(MessageFor(request), request, sink);
  }

  net::awaitable<Status> StreamUnits(const UnitStreamRequest& request,
                                     UnitSink& sink) override {
    proto::ClientMessage m;
    auto* r = m.mutable_resume();
    r->set_mesh_id(url_.mesh_id);
    if (request.region) {
      const std::string text = FormatRegionShape(*request.region);
      if (std::holds_alternative<SphereRegion>(request.region->shape)) {
        r->set_region(text);
      } else {
        r->set_view(text);
        if (request.region->screen_error_px) r->set_screen_error(*request.region->screen_error_px);
      }
    } else {
      r->set_order(ProgressionName(request.order));
    }
    // An empty held set is still a session of units: the region or order
    // says so; with neither, the order's packets (the same units).
    r->set_held(request.held);
    r->set_container(pinned_);
    if (request.max_level >= 0) r->set_max_level(static_cast<uint32_t>(request.max_level));
    if (request.budget) r->set_budget(*request.budget);
    r->set_rate(options_.pace_bytes_per_second);
    // The messages' sink: every Packet a unit.
    class Forward final : public StreamSink {
     public:
      explicit Forward(UnitSink& units) : units_(units) {}
      Status OnHead(const StreamHead&) override { return Status::Ok(); }
      Status OnBytes(std::string_view) override {
        return ParseError("bytes where messages were expected");
      }
      Status OnHeaderMessage(std::string_view) override {
        return ParseError("a stream header in the answer to a resume");
      }
      Status OnPacketMessage(size_t, uint32_t id, std::string_view payload) override {
        return units_.OnUnit({id}, payload);
      }
      Status OnUnitMessage(size_t, StreamUnit unit, std::string_view payload) override {
        return units_.OnUnit(unit, payload);
      }

     private:
      UnitSink& units_;
    } forward(sink);
    StreamRequest limits;  // for the reader's header limit: no header comes
    Status s = co_await Request(m, limits, forward);
    server_stream_.reset();  // a stream of units: never continued by a refine
    co_return s;
  }

  void Close() override {
    plain_.reset();
    tls_.reset();
    buffer_.clear();
    server_stream_.reset();
  }

  bool CanStreamPayloadsFromStart() const override { return true; }

 private:
  // Where the server's stream on the open connection stopped (after Done).
  struct ServerStream {
    Progression order;
    int max_level;
    size_t next_cursor;
  };

  bool connected() const { return plain_.has_value() || tls_.has_value(); }

  // A refine when the open connection's stream stopped exactly where this
  // request starts, else a start (from 0 without the header) or a resume.
  proto::ClientMessage MessageFor(const StreamRequest& r) const {
    proto::ClientMessage m;
    const bool continues =
        connected() && server_stream_ && server_stream_->order == r.order &&
        server_stream_->max_level == r.max_level &&
        server_stream_->next_cursor == r.from && (r.from > 0 || r.header_held);
    if (continues) {
      m.mutable_refine()->set_extra_bytes(r.budget.value_or(kWholeOrder));
      return m;
    }
    if (r.from == 0 && !r.header_held) {
      auto* s = m.mutable_start();
      s->set_mesh_id(url_.mesh_id);
      s->set_order(ProgressionName(r.order));
      if (r.max_level >= 0)
        s->set_max_level(static_cast<uint32_t>(r.max_level));
      if (r.budget) s->set_budget(*r.budget);
      s->set_rate(options_.pace_bytes_per_second);
      s->set_container(pinned_);
      return m;
    }
    return ResumeFor(r);
  }

  proto::ClientMessage ResumeFor(const StreamRequest& r) const {
    proto::ClientMessage m;
    auto* s = m.mutable_resume();
    s->set_mesh_id(url_.mesh_id);
    s->set_order(ProgressionName(r.order));
    if (r.max_level >= 0) s->set_max_level(static_cast<uint32_t>(r.max_level));
    s->set_cursor(static_cast<uint32_t>(r.from));
    if (r.budget) s->set_budget(*r.budget);
    s->set_rate(options_.pace_bytes_per_second);
    s->set_container(pinned_);
    return m;
  }

  net::awaitable<Status> Request(proto::ClientMessage m,
                                 const StreamRequest& request,
                                 StreamSink& sink) {
    const bool reused = connected();
    if (!reused) MWC_CO_RETURN_IF_ERROR(co_await Connect());
    bool answered = false;
    Status s = co_await ExchangeOnce(m, request, sink, answered);
    if (!s.ok() && s.code() == StatusCode::kIoError && reused && !answered) {
      // The idle connection was closed under us (its read timeout, a
      // restarted server): once more on a fresh one, where the server holds
      // no stream, so a refine becomes a resume.
      MWC_CO_RETURN_IF_ERROR(co_await Connect());
      if (m.has_refine()) m = ResumeFor(request);
      s = co_await ExchangeOnce(m, request, sink, answered);
    }
    if (!s.ok()) Close();
    co_return s;
  }

  net::awaitable<Status> Connect() {
    Close();
    Status s;
    if (!url_.server.tls) {
      plain_.emplace(executor_);
      s = co_await ConnectTcp(plain_->next_layer(), url_.server, options_);
      if (s.ok()) s = co_await Handshake(*plain_);
    } else {
      if (!ssl_context_) {
        auto ctx = MakeTlsContext(options_);
        if (!ctx.ok()) co_return ctx.status();
        ssl_context_ = std::move(*ctx);
      }
      tls_.emplace(executor_, *ssl_context_);
      s = co_await ConnectTls(tls_->next_layer(), url_.server, options_);
      if (s.ok()) s = co_await Handshake(*tls_);
    }
    if (!s.ok()) Close();
    co_return s;
  }

  template <class Ws>
  net::awaitable<Status> Handshake(Ws& ws) {
    // The WebSocket stream keeps its own timers: no read waits longer than
    // read_timeout for a frame (idle_timeout without pings).
    beast::get_lowest_layer(ws).expires_never();
    websocket::stream_base::timeout timeout{};
    timeout.handshake_timeout = options_.connect_timeout;
    timeout.idle_timeout = options_.read_timeout;
    timeout.keep_alive_pings = false;
    ws.set_option(timeout);
    ws.set_option(
        websocket::stream_base::decorator([](websocket::request_type& req) {
          req.set(http::field::user_agent, "meshwave-client/0.1");
        }));
    ws.binary(true);
    websocket::response_type response;
    auto [ec] = co_await ws.async_handshake(response, HostHeader(url_.server),
                                            "/v1/ws", Tuple());
    if (ec == websocket::error::upgrade_declined) {
      co_return StatusFromResponse(
          "GET /v1/ws (WebSocket upgrade)", response.result_int(),
          std::string(response.reason()), response.body());
    }
    if (ec) {
      co_return NetError("WebSocket handshake with " + url_.server.ToString(),
                         ec, options_.connect_timeout);
    }
    co_return Status::Ok();
  }

  net::awaitable<Status> ExchangeOnce(const proto::ClientMessage& m,
                                      const StreamRequest& request,
                                      StreamSink& sink, bool& answered) {
    if (tls_) co_return co_await Exchange(*tls_, m, request, sink, answered);
    co_return co_await Exchange(*plain_, m, request, sink, answered);
  }

  // Sends one request and consumes its answer up to Done.
  template <class Ws>
  net::awaitable<Status> Exchange(Ws& ws, const proto::ClientMessage& m,
                                  const StreamRequest& request,
                                  StreamSink& sink, bool& answered) {
    const std::string where = url_.server.ToString() + "/v1/ws";
    const std::string bytes = m.SerializeAsString();
    auto [wec, wn] = co_await ws.async_write(net::buffer(bytes), Tuple());
    if (wec)
      co_return NetError("sending to " + where, wec, options_.read_timeout);
    server_stream_.reset();  // until Done says where it stopped
    ServerMessageReader reader(m.has_start(), request.max_header_bytes, sink,
                               where);
    for (;;) {
      // Beast checks each frame's declared length against this before
      // reading its payload: a claimed 1 GiB header is refused unread.
      ws.read_message_max(reader.NextMessageLimit(kMessageLimit));
      buffer_.clear();
      auto [rec, rn] = co_await ws.async_read(buffer_, Tuple());
      if (rec == websocket::error::message_too_big) {
        co_return reader.TooLarge(kMessageLimit);
      }
      if (rec) {
        co_return NetError("reading from " + where, rec, options_.read_timeout);
      }
      answered = true;
      const auto data = buffer_.cdata();
      auto done = reader.OnMessage(
          std::string_view(static_cast<const char*>(data.data()), data.size()),
          ws.got_binary());
      if (!done.ok()) co_return done.status();
      // The container, once known, is named in every start and resume
      // (docs/API.md, "Re-encoded meshes"): CONFLICT rather than a mix.
      if (!reader.container().empty() && pinned_.empty()) {
        if (!IsValidContainerDigest(reader.container())) {
          co_return ParseError(where + " named a container that is not a digest");
        }
        pinned_ = reader.container();
      }
      if (*done) {
        server_stream_ = ServerStream{request.order, request.max_level,
                                      static_cast<size_t>(**done)};
        co_return Status::Ok();
      }
    }
  }

  net::any_io_executor executor_;
  MeshUrl url_;
  TransportOptions options_;
  std::unique_ptr<ssl::context> ssl_context_;
  std::optional<websocket::stream<beast::tcp_stream>> plain_;
  std::optional<websocket::stream<beast::ssl_stream<beast::tcp_stream>>> tls_;
  beast::flat_buffer buffer_;
  std::optional<ServerStream> server_stream_;
};

}  // namespace

std::unique_ptr<Transport> MakeWebSocketTransport(
    net::any_io_executor executor, const MeshUrl& url,
    const TransportOptions& options) {
  return std::make_unique<WebSocketTransport>(std::move(executor), url,
                                              options);
}

}  // namespace meshwave::client
