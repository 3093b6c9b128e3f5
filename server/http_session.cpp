#include "http_session.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "api_router.h"
#include "response.h"
#include "ws_session.h"

namespace meshwave::server {
namespace {

// A malformed request (as opposed to a closed or timed-out connection):
// the client is told with a 4xx before the connection closes.
bool IsMalformedRequest(beast::error_code ec) {
  return ec.category() == http::make_error_code(http::error::bad_target).category() &&
         ec != http::error::end_of_stream && ec != http::error::partial_message;
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, ServerContext& ctx, bool over_capacity)
    : stream_(std::move(socket)), ctx_(ctx), over_capacity_(over_capacity) {
  ctx_.metrics().ConnectionOpened();
  beast::error_code ec;
  const auto peer = stream_.socket().remote_endpoint(ec);
  if (!ec) client_ = peer.address().to_string();
}

HttpSession::~HttpSession() { ctx_.metrics().ConnectionClosed(); }

void HttpSession::Run() {
  net::dispatch(stream_.get_executor(),
                beast::bind_front_handler(&HttpSession::DoRead, shared_from_this()));
}

void HttpSession::Shutdown() {
  net::post(stream_.get_executor(), [self = shared_from_this()] {
    self->shutting_down_ = true;
    // An idle keep-alive connection has nothing in flight: close it now.
    // A busy one closes after its response (OnWrite).
    if (self->waiting_for_request_) {
      beast::error_code ec;
      self->stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
      self->stream_.cancel();
    }
  });
}

void HttpSession::DoRead() {
  if (shutting_down_) return DoClose();
  const auto& config = ctx_.config();
  parser_.emplace();
  parser_->header_limit(config.header_limit_bytes());
  // Beast checks Content-Length against the limit while parsing the
  // header, before we know whether this is an upload: start with the
  // larger limit and lower it in OnHeader.
  parser_->body_limit(std::max(config.body_limit_bytes(), config.upload_limit_bytes()));
  stream_.expires_after(std::chrono::seconds(config.idle_timeout_seconds()));
  waiting_for_request_ = true;
  if (buffer_.size() > 0) return DoReadHeader();  // a pipelined request is here
  stream_.async_read_some(buffer_.prepare(4096),
                          beast::bind_front_handler(&HttpSession::OnFirstBytes, shared_from_this()));
}

void HttpSession::OnFirstBytes(beast::error_code ec, size_t bytes) {
  if (ec) {
    waiting_for_request_ = false;
    return Fail(ec, "read");  // closed or idle too long
  }
  buffer_.commit(bytes);
  DoReadHeader();
}

void HttpSession::DoReadHeader() {
  // The idle timeout covers the wait for a request; once it has begun, its
  // header must be complete in header_timeout_seconds, so that clients
  // trickling headers byte by byte (slowloris) cannot hold connections.
  stream_.expires_after(std::chrono::seconds(ctx_.config().header_timeout_seconds()));
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::OnHeader, shared_from_this()));
}

Response HttpSession::ParseFailure(beast::error_code ec) {
  if (ec == http::error::header_limit) {
    return JsonError(http::status::request_header_fields_too_large, "request header too large");
  }
  if (ec == http::error::body_limit) {
    return JsonError(http::status::payload_too_large, "request body too large");
  }
  return JsonError(http::status::bad_request, "malformed HTTP request: " + ec.message());
}

void HttpSession::OnHeader(beast::error_code ec, size_t /*bytes*/) {
  waiting_for_request_ = false;
  started_ = std::chrono::steady_clock::now();
  if (ec == http::error::end_of_stream) return DoClose();
  if (ec) {
    // A client that sent something malformed gets told so; a timeout or a
    // reset ends the connection quietly.
    if (IsMalformedRequest(ec)) return DoWrite(ParseFailure(ec), true);
    return Fail(ec, "read header");
  }
  const auto& header = parser_->get();
  version_ = header.version();
  head_ = header.method() == http::verb::head;
  if (over_capacity_) {
    Response r = JsonError(http::status::service_unavailable, "too many connections");
    r.set(http::field::retry_after, "1");
    return DoWrite(std::move(r), true);
  }
  if (!ctx_.rate_limiter().Allow(client_)) {
    Response r = JsonError(http::status::too_many_requests, "too many requests from this client");
    r.set(http::field::retry_after, "1");
    return DoWrite(std::move(r), true);
  }
  if (beast::websocket::is_upgrade(header)) {
    if (auto refusal = CheckWebSocketUpgrade(ctx_, header)) return DoWrite(std::move(*refusal), true);
    // The socket moves to a WebSocket session; this one ends here.
    stream_.expires_never();
    auto ws = std::make_shared<WsSession>(stream_.release_socket(), ctx_);
    ctx_.Register(ws);
    ws->Run(parser_->release());
    return;
  }
  HeaderDecision d = InspectHeader(ctx_, header);
  if (d.reject) return DoWrite(std::move(*d.reject), true);
  if (!d.upload) {
    const uint64_t limit = ctx_.config().body_limit_bytes();
    if (parser_->content_length().value_or(0) > limit) {
      return DoWrite(ParseFailure(http::error::body_limit), true);
    }
    parser_->body_limit(limit);  // for chunked bodies
  } else {
    parser_->body_limit(ctx_.config().upload_limit_bytes());
    // curl and others wait for this before sending a large body.
    if (beast::iequals(header[http::field::expect], "100-continue")) {
      continue_ = std::make_shared<http::response<http::empty_body>>(http::status::continue_, version_);
      return http::async_write(stream_, *continue_,
                               beast::bind_front_handler(&HttpSession::OnContinueSent,
                                                         shared_from_this()));
    }
  }
  DoReadBody();
}

void HttpSession::OnContinueSent(beast::error_code ec, size_t /*bytes*/) {
  continue_.reset();
  if (ec) return Fail(ec, "write 100-continue");
  DoReadBody();
}

void HttpSession::DoReadBody() {
  // Uploads may be slow to arrive: the write timeout bounds them.
  stream_.expires_after(std::chrono::seconds(ctx_.config().write_timeout_seconds()));
  http::async_read(stream_, buffer_, *parser_,
                   beast::bind_front_handler(&HttpSession::OnBody, shared_from_this()));
}

void HttpSession::OnBody(beast::error_code ec, size_t /*bytes*/) {
  if (ec) {
    if (IsMalformedRequest(ec)) return DoWrite(ParseFailure(ec), true);
    return Fail(ec, "read body");
  }
  stream_.expires_never();  // an upload may take a while to ingest
  auto self = shared_from_this();
  // The guard keeps io threads running while an upload is ingested on the
  // worker, so a shutdown still sends its response.
  auto work = net::make_work_guard(stream_.get_executor());
  HandleRequest(ctx_, parser_->release(), [self, work](Response r) {
    net::post(self->stream_.get_executor(), [self, work, r = std::move(r)]() mutable {
      self->DoWrite(std::move(r), false);
    });
  });
}

void HttpSession::DoWrite(Response response, bool close) {
  const bool keep_alive = !close && !shutting_down_ && !ctx_.stopping() &&
                          (!parser_ || parser_->keep_alive());
  response.version(version_);
  response.keep_alive(keep_alive);
  response.set(http::field::server, "meshwave");
  response.prepare_payload();
  if (head_) {
    // Same header as GET, no body.
    const uint64_t length = response.body().size();
    response.body() = {};
    response.content_length(length);
  }
  response_ = std::make_shared<Response>(std::move(response));
  stream_.expires_after(std::chrono::seconds(ctx_.config().write_timeout_seconds()));
  http::async_write(stream_, *response_,
                    beast::bind_front_handler(&HttpSession::OnWrite, shared_from_this(),
                                              !keep_alive));
}

void HttpSession::OnWrite(bool close, beast::error_code ec, size_t bytes) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  ctx_.metrics().RecordRequest(response_->result_int(), bytes, seconds);
  response_.reset();
  if (ec) return Fail(ec, "write");
  if (close || shutting_down_) return DoClose();
  DoRead();
}

void HttpSession::DoClose() {
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  if (ec) return;
  // Lingering close: read and drop what the client still sends (the rest
  // of a refused request), because closing with unread bytes makes the
  // kernel send a reset that can destroy our response before the client
  // reads it. Bounded in time and bytes.
  stream_.expires_after(std::chrono::seconds(2));
  DoDrain();
}

void HttpSession::DoDrain() {
  stream_.async_read_some(
      net::buffer(drain_),
      [self = shared_from_this()](beast::error_code ec, size_t bytes) {
        self->drained_ += bytes;
        if (ec || self->drained_ > kMaxDrainBytes) return;  // the session ends
        self->DoDrain();
      });
}

void HttpSession::Fail(beast::error_code ec, const char* what) {
  // Expected ends of a connection are not worth a log line.
  if (ec == net::error::operation_aborted || ec == beast::error::timeout ||
      ec == net::error::eof || ec == net::error::connection_reset ||
      ec == http::error::end_of_stream || ec == net::error::broken_pipe ||
      ec == http::error::partial_message) {
    return;
  }
  spdlog::debug("http session {}: {}", what, ec.message());
}

}  // namespace meshwave::server
