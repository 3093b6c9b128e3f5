#include "ws_session.h"

#include <spdlog/spdlog.h>

#include <array>

#include "meshwave/container.h"
#include "meshwave/region_text.h"
#include "response.h"

namespace meshwave::server {
namespace {

// Small messages (selections, errors) waiting behind the write in flight.
// Each client message adds at most one, so past this many the session stops
// reading until the queue drains: a client flooding requests is slowed down
// instead of growing the queue.
constexpr size_t kMaxQueued = 16;
// Refines sent while a stream runs, each owed its Done: past this many the
// next one is refused (a client has no use for more, and the list is kept
// bounded).
constexpr size_t kMaxPendingDone = 64;

std::string RemoteName(const tcp::socket& socket) {
  beast::error_code ec;
  const auto ep = socket.remote_endpoint(ec);
  if (ec) return "?";
  return ep.address().to_string() + ":" + std::to_string(ep.port());
}

proto::Selection ToProto(const StreamCursor::Selection& selection) {
  proto::Selection s;
  s.set_from_cursor(static_cast<uint32_t>(selection.from));
  s.set_next_cursor(static_cast<uint32_t>(selection.next));
  s.set_order_packets(static_cast<uint32_t>(selection.order_length));
  s.set_bytes(selection.bytes);
  return s;
}

}  // namespace

WsSession::WsSession(tcp::socket&& socket, ServerContext& ctx)
    : ws_(std::move(socket)),
      ctx_(ctx),
      pacing_timer_(ws_.get_executor()),
      keepalive_timer_(ws_.get_executor()),
      remote_(RemoteName(beast::get_lowest_layer(ws_).socket())),
      opened_(std::chrono::steady_clock::now()) {
  ctx_.metrics().WebSocketOpened();
}

WsSession::~WsSession() {
  ctx_.metrics().WebSocketClosed();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - opened_)
          .count();
  spdlog::info("ws {} closed after {:.1f} s: {} requests, {} packets, {} bytes",
               remote_, seconds, requests_, packets_sent_, bytes_sent_);
}

void WsSession::Run(const http::request<http::string_body>& upgrade) {
  const auto& config = ctx_.config();
  websocket::stream_base::timeout timeout{};
  timeout.handshake_timeout =
      std::chrono::seconds(config.idle_timeout_seconds());
  // Keep-alive is the session's own (ArmKeepAlive): Beast's idle timeout
  // would drop a silent client without a close frame.
  timeout.idle_timeout = websocket::stream_base::none();
  timeout.keep_alive_pings = false;
  ws_.set_option(timeout);
  ws_.set_option(
      websocket::stream_base::decorator([](websocket::response_type& res) {
        res.set(http::field::server, "meshwave");
        if (res.result() != http::status::switching_protocols) {
          // Beast refused the handshake (no key, version not 13, ...) with
          // a plain-text reason: JSON, as every other error of the API.
          res.body() = JsonErrorBody("WebSocket handshake refused: " + res.body());
          SetJsonErrorHeaders(res);
          res.prepare_payload();
        }
      }));
  // Pings, pongs and close frames count as hearing from the client.
  ws_.control_callback([this](websocket::frame_type, beast::string_view) {
    last_heard_ = std::chrono::steady_clock::now();
  });
  ws_.read_message_max(config.websocket_message_limit_bytes());
  ws_.binary(true);
  // One frame per message: payloads go out without being copied in pieces.
  ws_.auto_fragment(false);
  ws_.async_accept(upgrade, beast::bind_front_handler(&WsSession::OnAccept,
                                                      shared_from_this()));
}

void WsSession::Shutdown() {
  net::post(ws_.get_executor(), [self = shared_from_this()] {
    if (self->closing_) return;
    if (!self->writing_)
      return self->DoClose({websocket::close_code::going_away, "the server is stopping"});
    self->close_after_write_ = true;
  });
}

void WsSession::OnAccept(beast::error_code ec) {
  if (ec) return Fail(ec, "accept");
  spdlog::info("ws {} open", remote_);
  last_heard_ = std::chrono::steady_clock::now();
  ArmKeepAlive();
  DoRead();
}

void WsSession::DoRead() {
  if (reading_ || closing_) return;
  reading_ = true;
  ws_.async_read(read_buffer_, beast::bind_front_handler(&WsSession::OnRead,
                                                         shared_from_this()));
}

void WsSession::OnRead(beast::error_code ec, size_t /*bytes*/) {
  reading_ = false;
  if (ec) {
    // The client closed, the connection broke or stayed silent past the
    // idle time, or a message was too large (Beast has sent close 1009).
    closing_ = true;
    StopTimers();
    return Fail(ec, "read");
  }
  last_heard_ = std::chrono::steady_clock::now();
  if (!ws_.got_binary()) {
    read_buffer_.clear();
    return DoClose({websocket::close_code::unknown_data, "binary frames only"});
  }
  const auto data = read_buffer_.cdata();
  auto request = ParseClientMessage(
      std::string_view(static_cast<const char*>(data.data()), data.size()),
      WsLimits{ctx_.config().websocket_message_limit_bytes()});
  read_buffer_.clear();
  ++requests_;
  if (!request.ok()) {
    SendError(proto::Error::BAD_REQUEST, request.status().message());
  } else {
    try {
      Handle(*request);
    } catch (const std::exception& e) {
      spdlog::error("ws {}: {}", remote_, e.what());
      SendError(proto::Error::UNAVAILABLE, "internal error");
    }
  }
  if (queue_.size() < kMaxQueued) DoRead();  // else Pump resumes reading
  Pump();
}

void WsSession::Handle(const ClientRequest& request) {
  if (ctx_.stopping()) {
    return SendError(proto::Error::UNAVAILABLE, "the server is stopping");
  }
  if (request.kind == ClientRequest::Kind::kRefine) return RefineStream(request);
  if (streaming()) {
    return SendError(proto::Error::BAD_REQUEST,
                     "a stream is in progress: wait for Done, or send refine");
  }
  StartStream(request);
}

void WsSession::StartStream(const ClientRequest& r) {
  auto found = ctx_.cache().Get(r.mesh_id);
  if (!found.ok()) {
    return SendError(
        proto::Error::UNAVAILABLE,
        "mesh " + r.mesh_id + " cannot be served: " + found.status().message());
  }
  if (!*found)
    return SendError(proto::Error::NOT_FOUND, "no mesh with id " + r.mesh_id);
  const bool start = r.kind == ClientRequest::Kind::kStart;
  auto selection = stream_.Start(std::move(*found), r.stream, start, r.header_only);
  if (!selection.ok()) return SendError(selection.status());
  SetPacing(r.rate);
  const StreamRequest& q = r.stream;
  spdlog::info("ws {}: {} mesh {} {} max_level {} from {} to {} ({} bytes) rate {} B/s", remote_,
               start ? "start" : "resume", stream_.mesh()->entry().id,
               q.region ? "region " + FormatRegionShape(*q.region)
                        : std::string("order ") + ProgressionName(q.order),
               q.max_level, selection->from, selection->next, selection->bytes, r.rate);
  proto::ServerMessage m;
  if (start) {
    m.mutable_start()->set_header(stream_.mesh()->header_bytes());
    *m.mutable_start()->mutable_selection() = ToProto(*selection);
  } else {
    *m.mutable_selection() = ToProto(*selection);
  }
  Queue(m, start);
}

void WsSession::SetPacing(uint64_t rate) {
  const auto now = TokenBucket::Clock::now();
  if (rate == 0) {
    pacer_.reset();
  } else if (pacer_ && pacer_->rate() == rate) {
    pacer_->DropCredit(now);
  } else {
    pacer_.emplace(rate, now);
  }
}

void WsSession::RefineStream(const ClientRequest& r) {
  if (stream_.pending() >= kMaxPendingDone) {
    return SendError(proto::Error::BAD_REQUEST,
                     std::to_string(kMaxPendingDone) +
                         " requests of this stream are still running: wait for a Done");
  }
  const bool was_streaming = streaming();
  auto selection =
      stream_.Refine(r.extra_bytes, r.stream.region,
                     r.refine_order ? std::optional<Progression>(r.stream.order) : std::nullopt);
  if (!selection.ok()) return SendError(selection.status());
  proto::ServerMessage m;
  *m.mutable_selection() = ToProto(*selection);
  spdlog::debug("ws {}: refine {} bytes, to {}", remote_, r.extra_bytes, selection->next);
  if (!was_streaming && pacer_) pacer_->DropCredit(TokenBucket::Clock::now());
  Queue(m, false);
}

void WsSession::SendError(const Status& status) {
  SendError(status.code() == StatusCode::kInvalidArgument ? proto::Error::BAD_REQUEST
                                                          : proto::Error::UNAVAILABLE,
            status.message());
}

void WsSession::SendError(proto::Error::Code code, const std::string& message) {
  queue_.push_back({ErrorMessage(code, message), false});
}

void WsSession::Queue(const proto::ServerMessage& message, bool paced) {
  queue_.push_back({message.SerializeAsString(), paced});
}

void WsSession::Pump() {
  if (writing_ || closing_) return;
  auto write = [this](auto buffers) {
    writing_ = true;
    ws_.async_write(buffers, beast::bind_front_handler(&WsSession::OnWrite,
                                                       shared_from_this()));
  };
  if (!queue_.empty()) {
    if (queue_.front().paced && !MayWriteNow(queue_.front().bytes.size()))
      return;
    in_flight_ = std::move(queue_.front().bytes);
    queue_.pop_front();
    if (queue_.size() < kMaxQueued / 2) DoRead();
    return write(net::buffer(in_flight_));
  }
  // One Done per request, once the units it selected are out.
  if (const auto done = stream_.DoneDue()) {
    proto::ServerMessage m;
    m.mutable_done()->set_next_cursor(static_cast<uint32_t>(done->next));
    m.mutable_done()->set_complete(done->complete);
    stream_.TakeDone();
    in_flight_ = m.SerializeAsString();
    return write(net::buffer(in_flight_));
  }
  if (const auto next = stream_.Peek()) {
    const std::string_view payload = next->payload;
    const std::optional<uint32_t> part =
        next->unit.whole() ? std::nullopt : std::optional<uint32_t>(next->unit.part);
    std::string prefix = PacketMessagePrefix(static_cast<uint32_t>(next->cursor), next->unit.id,
                                             payload.size(), part);
    if (!MayWriteNow(prefix.size() + payload.size())) return;
    in_flight_ = std::move(prefix);
    in_flight_mesh_ = stream_.shared_mesh();
    stream_.Advance();
    ++packets_sent_;
    return write(std::array<net::const_buffer, 2>{
        net::buffer(in_flight_), net::buffer(payload.data(), payload.size())});
  }
}

bool WsSession::MayWriteNow(uint64_t bytes) {
  if (!pacer_) return true;
  const auto wait = pacer_->Take(bytes, TokenBucket::Clock::now());
  if (wait == TokenBucket::Clock::duration::zero()) return true;
  if (!timer_armed_) {
    timer_armed_ = true;
    pacing_timer_.expires_after(wait);
    pacing_timer_.async_wait(beast::bind_front_handler(
        &WsSession::OnPacingTimer, shared_from_this()));
  }
  return false;
}

void WsSession::OnPacingTimer(beast::error_code ec) {
  timer_armed_ = false;
  if (ec) return;  // cancelled: the session ends
  Pump();
}

void WsSession::OnWrite(beast::error_code ec, size_t bytes) {
  writing_ = false;
  in_flight_mesh_.reset();
  bytes_sent_ += bytes;
  ctx_.metrics().AddWebSocketBytes(bytes);
  if (ec) {
    closing_ = true;
    StopTimers();
    return Fail(ec, "write");
  }
  if (close_after_write_) {
    return DoClose({websocket::close_code::going_away, "the server is stopping"});
  }
  Pump();
}

void WsSession::DoClose(websocket::close_reason reason) {
  if (closing_) return;
  closing_ = true;
  pacing_timer_.cancel();
  // The pending read completes when the client answers the close; a client
  // that does not within a ping period loses the socket (OnKeepAlive).
  keepalive_timer_.expires_after(
      std::chrono::seconds(ctx_.config().websocket_ping_seconds()));
  keepalive_timer_.async_wait(beast::bind_front_handler(
      &WsSession::OnKeepAlive, shared_from_this()));
  ws_.async_close(reason, [self = shared_from_this()](beast::error_code ec) {
    if (ec) return self->Fail(ec, "close");
    self->StopTimers();
  });
}

void WsSession::ArmKeepAlive() {
  const auto ping = std::chrono::seconds(ctx_.config().websocket_ping_seconds());
  const auto silent = std::chrono::steady_clock::now() - last_heard_;
  // Next due: the ping after `ping` of silence, then the close after twice.
  keepalive_timer_.expires_at(last_heard_ + (silent >= ping ? 2 * ping : ping));
  keepalive_timer_.async_wait(beast::bind_front_handler(
      &WsSession::OnKeepAlive, shared_from_this()));
}

void WsSession::OnKeepAlive(beast::error_code ec) {
  if (ec) return;  // cancelled or re-armed
  if (closing_) {
    // The close frame got no answer (or could not even be written past a
    // client that reads nothing): drop the connection.
    beast::get_lowest_layer(ws_).close();
    return;
  }
  const auto ping = std::chrono::seconds(ctx_.config().websocket_ping_seconds());
  const auto now = std::chrono::steady_clock::now();
  if (now - last_heard_ >= 2 * ping) {
    spdlog::info("ws {}: no answer to keep-alive pings for {} s, closing", remote_,
                 2 * ctx_.config().websocket_ping_seconds());
    return DoClose({websocket::close_code::policy_error, "keep-alive pings unanswered"});
  }
  if (now - last_heard_ >= ping && last_ping_ <= last_heard_ && !ping_in_flight_) {
    last_ping_ = now;
    ping_in_flight_ = true;
    ws_.async_ping({}, [self = shared_from_this()](beast::error_code) {
      self->ping_in_flight_ = false;
    });
  }
  ArmKeepAlive();
}

void WsSession::StopTimers() {
  pacing_timer_.cancel();
  keepalive_timer_.cancel();
}

void WsSession::Fail(beast::error_code ec, const char* what) {
  // Expected ends of a connection are not worth a log line.
  if (ec == websocket::error::closed || ec == net::error::operation_aborted ||
      ec == net::error::eof || ec == net::error::connection_reset ||
      ec == net::error::broken_pipe) {
    return;
  }
  spdlog::info("ws {}: {}: {}", remote_, what, ec.message());
}

}  // namespace meshwave::server
