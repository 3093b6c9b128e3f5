#include "ws_session.h"

#include <spdlog/spdlog.h>

#include <array>

#include "meshwave/container.h"
#include "meshwave/region_text.h"
#include "meshwave/stream_units.h"
#include "response.h"
#include "stream_plan.h"
#include "stream_query.h"

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

proto::Selection ToProto(const StreamPlan& plan, size_t from) {
  proto::Selection s;
  s.set_from_cursor(static_cast<uint32_t>(from));
  s.set_next_cursor(static_cast<uint32_t>(plan.selection.next_cursor));
  s.set_order_packets(static_cast<uint32_t>(plan.order->size()));
  s.set_bytes(plan.selection.bytes);
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
  std::shared_ptr<const ServedMesh> mesh = std::move(*found);
  if (r.units()) {
    if (StartUnits(r, std::move(mesh))) SetPacing(r.rate);
    return;
  }
  const bool start = r.kind == ClientRequest::Kind::kStart;
  uint64_t budget = r.budget.value_or(kMaxBudget);
  // Exactly the header's container: no packet fits beside it.
  if (r.header_only) budget = ContainerSize(mesh->header(), {});
  const uint64_t from = start ? 0 : r.cursor;
  auto plan = PlanStream(*mesh, r.order, r.max_level, from, budget, start);
  if (!plan.ok())
    return SendError(proto::Error::BAD_REQUEST, plan.status().message());

  mesh_ = std::move(mesh);
  order_ = plan->order;
  max_level_ = r.max_level;
  units_ = nullptr;
  held_.reset();
  selected_.clear();
  cursor_ = from;
  end_ = plan->selection.next_cursor;
  done_at_.push_back({end_, plan->complete()});
  SetPacing(r.rate);
  spdlog::info(
      "ws {}: {} mesh {} order {} max_level {} from {} to {} ({} bytes) rate "
      "{} B/s",
      remote_, start ? "start" : "resume", mesh_->entry().id,
      ProgressionName(r.order), r.max_level, from, end_, plan->selection.bytes,
      r.rate);
  proto::ServerMessage m;
  if (start) {
    m.mutable_start()->set_header(mesh_->header_bytes());
    *m.mutable_start()->mutable_selection() = ToProto(*plan, from);
  } else {
    *m.mutable_selection() = ToProto(*plan, from);
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

bool WsSession::StartUnits(const ClientRequest& r, std::shared_ptr<const ServedMesh> mesh) {
  if (Status s = mesh->CheckLevelLimit(r.max_level); !s.ok()) {
    SendError(proto::Error::BAD_REQUEST, s.message());
    return false;
  }
  auto table = mesh->units();
  if (!table.ok()) {
    SendError(proto::Error::UNAVAILABLE, table.status().message());
    return false;
  }
  HeldUnits held = (*table)->nothing_held();
  if (r.held) {
    if (Status s = DecodeHeldUnits(*r.held, (*table)->numbering(), held); !s.ok()) {
      SendError(proto::Error::BAD_REQUEST, s.message());
      return false;
    }
  }
  const bool start = r.kind == ClientRequest::Kind::kStart;
  // A start's budget counts the header, as a container's does.
  const uint64_t header = start ? ContainerSize(mesh->header(), {}) : 0;
  uint64_t budget = r.budget.value_or(kMaxBudget);
  if (r.header_only) budget = header;
  if (budget < header) {
    SendError(proto::Error::BAD_REQUEST, "budget " + std::to_string(budget) +
                                             " is smaller than the stream header (" +
                                             std::to_string(header) + " bytes)");
    return false;
  }
  mesh_ = std::move(mesh);
  order_ = nullptr;
  max_level_ = r.max_level;
  units_ = *table;
  held_.emplace(std::move(held));
  unit_request_ = UnitRequest{r.region, r.order, r.max_level, 0};
  selected_.clear();
  cursor_ = end_ = 0;
  const UnitPlan plan = SelectUnits(budget - header);
  spdlog::info("ws {}: {} mesh {} {} max_level {}: {} units ({} bytes)", remote_,
               start ? "start" : "resume", mesh_->entry().id,
               r.region ? "region " + FormatRegionShape(*r.region)
                        : std::string("order ") + ProgressionName(r.order),
               r.max_level, plan.units.size(), plan.bytes);
  proto::ServerMessage m;
  if (start) {
    m.mutable_start()->set_header(mesh_->header_bytes());
    *m.mutable_start()->mutable_selection() = UnitSelection(0, plan, header + plan.bytes);
  } else {
    *m.mutable_selection() = UnitSelection(0, plan, plan.bytes);
  }
  Queue(m, start);
  return true;
}

bool WsSession::SwitchToUnits() {
  if (units_) return true;
  auto table = mesh_->units();
  if (!table.ok()) {
    SendError(proto::Error::UNAVAILABLE, table.status().message());
    return false;
  }
  units_ = *table;
  held_.emplace(units_->nothing_held());
  // Cursors keep counting messages: packets selected so far are units.
  for (size_t k = 0; k < end_; ++k) {
    selected_.push_back({(*order_)[k]});
    held_->Add({(*order_)[k]});
  }
  unit_request_.max_level = max_level_;
  order_ = nullptr;
  return true;
}

UnitPlan WsSession::SelectUnits(uint64_t budget) {
  unit_request_.budget = budget;
  // The level limit was checked when the stream started.
  UnitPlan plan = *PlanUnits(*mesh_, *units_, *held_, unit_request_);
  for (const StreamUnit& u : plan.units) {
    held_->Add(u);
    selected_.push_back(u);
  }
  end_ = selected_.size();
  done_at_.push_back({end_, plan.complete});
  return plan;
}

proto::Selection WsSession::UnitSelection(size_t from, const UnitPlan& plan,
                                          uint64_t bytes) const {
  proto::Selection s;
  s.set_from_cursor(static_cast<uint32_t>(from));
  s.set_next_cursor(static_cast<uint32_t>(from + plan.units.size()));
  s.set_order_packets(static_cast<uint32_t>(units_->UnitsBelow(max_level_)));
  s.set_bytes(bytes);
  return s;
}

void WsSession::RefineStream(const ClientRequest& r) {
  if (!mesh_) {
    return SendError(proto::Error::BAD_REQUEST,
                     "nothing to refine: send start or resume first");
  }
  if (done_at_.size() >= kMaxPendingDone) {
    return SendError(proto::Error::BAD_REQUEST,
                     std::to_string(kMaxPendingDone) +
                         " requests of this stream are still running: wait for a Done");
  }
  const bool changes = r.region || r.refine_order;
  if (changes || units_) {
    if (!SwitchToUnits()) return;
    if (changes) {
      unit_request_.region = r.region;
      unit_request_.order = r.order;
    }
    const size_t from = end_;
    const UnitPlan plan = SelectUnits(r.extra_bytes);
    proto::ServerMessage m;
    *m.mutable_selection() = UnitSelection(from, plan, plan.bytes);
    spdlog::debug("ws {}: refine {} bytes, {} units", remote_, r.extra_bytes, plan.units.size());
    if (!streaming() && pacer_) pacer_->DropCredit(TokenBucket::Clock::now());
    return Queue(m, false);
  }
  StreamPlan plan;
  plan.order = order_;
  plan.selection = SelectPayloads(mesh_->header(), *order_, r.extra_bytes, end_);
  proto::ServerMessage m;
  *m.mutable_selection() = ToProto(plan, end_);
  spdlog::debug("ws {}: refine {} bytes, to {}", remote_, r.extra_bytes,
                plan.selection.next_cursor);
  end_ = plan.selection.next_cursor;
  if (!streaming() && pacer_) pacer_->DropCredit(TokenBucket::Clock::now());
  done_at_.push_back({end_, plan.complete()});
  Queue(m, false);
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
  // One Done per request, once the packets it selected are out.
  if (!done_at_.empty() && cursor_ == done_at_.front().end) {
    proto::ServerMessage m;
    m.mutable_done()->set_next_cursor(static_cast<uint32_t>(cursor_));
    m.mutable_done()->set_complete(done_at_.front().complete);
    done_at_.pop_front();
    in_flight_ = m.SerializeAsString();
    return write(net::buffer(in_flight_));
  }
  if (mesh_ && cursor_ < end_) {
    const StreamUnit unit = order_ ? StreamUnit{(*order_)[cursor_]} : selected_[cursor_];
    std::string_view payload = mesh_->payload(unit.id);
    std::optional<uint32_t> part;
    if (!unit.whole()) {
      payload = units_->Payload(payload, unit);
      part = unit.part;
    }
    std::string prefix =
        PacketMessagePrefix(static_cast<uint32_t>(cursor_), unit.id, payload.size(), part);
    if (!MayWriteNow(prefix.size() + payload.size())) return;
    in_flight_ = std::move(prefix);
    in_flight_mesh_ = mesh_;
    ++cursor_;
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
