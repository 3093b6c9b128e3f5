#include "http_session.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "api_router.h"
#include "http_head.h"
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

// The lingering close's bound in time (DoClose).
constexpr auto kDrainTime = std::chrono::seconds(2);

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, ServerContext& ctx, bool over_capacity)
    : socket_(std::move(socket)),
      deadline_(socket_.get_executor()),
      ctx_(ctx),
      over_capacity_(over_capacity) {
  ctx_.metrics().ConnectionOpened();
  beast::error_code ec;
  const auto peer = socket_.remote_endpoint(ec);
  if (!ec) client_ = peer.address().to_string();
}

HttpSession::~HttpSession() { ctx_.metrics().ConnectionClosed(); }

void HttpSession::Run() {
  // Past a deadline the socket is closed: the operation waiting on it ends
  // with operation_aborted, and the session with it.
  deadline_.Bind(weak_from_this(), [this] { OnDeadline(); });
  net::dispatch(socket_.get_executor(),
                beast::bind_front_handler(&HttpSession::DoRead, shared_from_this()));
}

void HttpSession::Shutdown() {
  net::post(socket_.get_executor(), [self = shared_from_this()] {
    self->shutting_down_ = true;
    // An idle keep-alive connection has nothing in flight: close it now.
    // A busy one closes after its response (OnWrite).
    if (self->waiting_for_request_) {
      beast::error_code ec;
      self->socket_.shutdown(tcp::socket::shutdown_both, ec);
      self->socket_.cancel(ec);
    }
  });
}

void HttpSession::OnDeadline() {
  beast::error_code ec;
  socket_.close(ec);
}

void HttpSession::DoRead() {
  if (shutting_down_) return DoClose();
  const auto& config = ctx_.config();
  cacheable_ = false;
  parser_.emplace();
  parser_->header_limit(config.header_limit_bytes());
  // Beast checks Content-Length against the limit while parsing the
  // header, before we know whether this is an upload: no limit until
  // OnHeader, which checks the length against the one that applies (and
  // names it) before a byte of the body is read.
  parser_->body_limit(boost::none);
  deadline_.ExpiresAfter(std::chrono::seconds(config.idle_timeout_seconds()));
  waiting_for_request_ = true;
  if (buffer_.size() > 0) return ParseHeader();  // a pipelined request is here
  // (Waiting with async_wait and then reading saves the recv that fails
  // at first, but Asio's reactor then makes an epoll_ctl call per wait
  // instead: no gain (perf: recv 8 -> 3 %, epoll_ctl 0 -> 4.7 %).)
  socket_.async_read_some(buffer_.prepare(4096),
                          beast::bind_front_handler(&HttpSession::OnFirstBytes, shared_from_this()));
}

void HttpSession::OnFirstBytes(beast::error_code ec, size_t bytes) {
  if (ec) {
    waiting_for_request_ = false;
    return Fail(ec, "read");  // closed or idle too long
  }
  buffer_.commit(bytes);
  ParseHeader();
}

void HttpSession::ParseHeader() {
  // Most requests arrive whole in their first read: parsed here, without
  // an asynchronous read that would complete at once.
  beast::error_code ec;
  size_t used = 0;
  while (!ec && buffer_.size() > 0 && !parser_->is_header_done()) {
    const size_t n = parser_->put(buffer_.data(), ec);
    buffer_.consume(n);
    used += n;
    if (n == 0 && !ec) break;
  }
  if (ec == http::error::need_more) ec = {};
  if (ec || parser_->is_header_done()) return OnHeader(ec, used);
  // The idle timeout covers the wait for a request; once it has begun, its
  // header must be complete in header_timeout_seconds, so that clients
  // trickling headers byte by byte (slowloris) cannot hold connections.
  deadline_.ExpiresAfter(std::chrono::seconds(ctx_.config().header_timeout_seconds()));
  http::async_read_header(socket_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::OnHeader, shared_from_this()));
}

Response HttpSession::ParseFailure(beast::error_code ec) {
  if (ec == http::error::header_limit) {
    return JsonError(http::status::request_header_fields_too_large, "request header too large");
  }
  if (ec == http::error::body_limit) {
    const uint64_t limit =
        upload_ ? ctx_.config().upload_limit_bytes() : ctx_.config().body_limit_bytes();
    return JsonError(http::status::payload_too_large,
                     std::string(upload_ ? "the upload" : "the request body") +
                         " is larger than this server's limit of " + std::to_string(limit) +
                         " bytes (" + (upload_ ? "upload_limit_bytes" : "body_limit_bytes") + ")");
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
  upload_ = false;
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
    deadline_.Cancel();
    auto ws = std::make_shared<WsSession>(std::move(socket_), ctx_);
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
    const uint64_t limit = ctx_.config().upload_limit_bytes();
    // Refused before a byte of the body is read (with Expect:
    // 100-continue, before the client sends it).
    if (const auto length = parser_->content_length(); length && *length > limit) {
      return DoWrite(JsonError(http::status::payload_too_large,
                               "the upload has " + std::to_string(*length) +
                                   " bytes, more than this server's limit of " +
                                   std::to_string(limit) + " bytes (upload_limit_bytes)"),
                     true);
    }
    parser_->body_limit(limit);  // for chunked bodies
    upload_ = true;
    // curl and others wait for this before sending a large body.
    if (beast::iequals(header[http::field::expect], "100-continue")) {
      continue_ = std::make_shared<http::response<http::empty_body>>(http::status::continue_, version_);
      deadline_.ExpiresAfter(std::chrono::seconds(ctx_.config().write_timeout_seconds()));
      return http::async_write(socket_, *continue_,
                               beast::bind_front_handler(&HttpSession::OnContinueSent,
                                                         shared_from_this()));
    }
  }
  // A request without a body (nearly every GET) is complete already.
  if (parser_->is_done()) return Answer();
  DoReadBody();
}

void HttpSession::OnContinueSent(beast::error_code ec, size_t /*bytes*/) {
  continue_.reset();
  if (ec) return Fail(ec, "write 100-continue");
  DoReadBody();
}

void HttpSession::DoReadBody() {
  // Uploads may be slow to arrive: the write timeout bounds them.
  deadline_.ExpiresAfter(std::chrono::seconds(ctx_.config().write_timeout_seconds()));
  http::async_read(socket_, buffer_, *parser_,
                   beast::bind_front_handler(&HttpSession::OnBody, shared_from_this()));
}

void HttpSession::OnBody(beast::error_code ec, size_t /*bytes*/) {
  if (ec) {
    if (IsMalformedRequest(ec)) return DoWrite(ParseFailure(ec), true);
    return Fail(ec, "read body");
  }
  Answer();
}

bool HttpSession::AnswerFromCache() {
  cacheable_ = false;
  ResponseCache& cache = ctx_.response_cache();
  if (!cache.enabled()) return false;
  // Which requests may be answered from the cache, and under what key:
  // the routes' rule (api_router.h).
  std::optional<std::string> key = ResponseCacheKey(parser_->get());
  if (!key) return false;
  cache_key_ = std::move(*key);
  cacheable_ = true;
  ResponseCache::Hit hit = cache.Get(cache_key_);
  if (!hit.response) return false;
  WriteCached(std::move(hit.response), std::move(hit.mesh), false);
  return true;
}

void HttpSession::Answer() {
  deadline_.ExpiresNever();  // an upload may take a while to ingest
  if (AnswerFromCache()) return;
  auto self = shared_from_this();
  // The guard keeps io threads running while an upload is ingested on the
  // worker, so a shutdown still sends its response.
  auto work = net::make_work_guard(socket_.get_executor());
  HandleRequest(ctx_, parser_->release(), [self, work](Response r) {
    net::post(self->socket_.get_executor(), [self, work, r = std::move(r)]() mutable {
      self->DoWrite(std::move(r), false);
    });
  });
}

bool HttpSession::KeepAlive(bool close) const {
  return !close && !shutting_down_ && !ctx_.stopping() && (!parser_ || parser_->keep_alive());
}

void HttpSession::DoWrite(Response response, bool close) {
  const unsigned status = response.result_int();
  if (cacheable_ && response.body().mesh && (status == 200 || status == 206)) {
    // A mesh endpoint's response: planned once, kept, and written from the
    // cache entry (the same bytes as below).
    cacheable_ = false;
    std::shared_ptr<const ServedMesh> mesh = response.body().mesh;
    auto cached = PlanResponse(std::move(response));
    ctx_.response_cache().Put(cache_key_, cached);
    return WriteCached(std::move(cached), std::move(mesh), close);
  }
  cacheable_ = false;
  const bool keep_alive = KeepAlive(close);
  const uint64_t body_bytes = response.body().size();
  head_bytes_.clear();
  AppendStatusLine(head_bytes_, version_, status);
  AppendFields(head_bytes_, response, body_bytes, head_);
  response_.emplace(std::move(response));
  status_ = status;
  buffers_.clear();
  QueueHead(keep_alive);
  QueueBody(response_->body().owned, response_->body().slices);
  StartWrite(keep_alive);
}

void HttpSession::QueueHead(bool keep_alive) {
  head_bytes_ += ConnectionField(version_, keep_alive);
  head_bytes_ += "\r\n";
  buffers_.emplace_back(head_bytes_.data(), head_bytes_.size());
}

void HttpSession::QueueBody(const std::string& owned,
                            const std::vector<net::const_buffer>& slices) {
  if (head_) return;  // HEAD: the same head as GET, no body
  if (!owned.empty()) buffers_.emplace_back(owned.data(), owned.size());
  buffers_.insert(buffers_.end(), slices.begin(), slices.end());
}

void HttpSession::WriteCached(std::shared_ptr<const CachedResponse> cached,
                              std::shared_ptr<const ServedMesh> mesh, bool close) {
  const bool keep_alive = KeepAlive(close);
  buffers_.clear();
  if (version_ >= 11 && keep_alive) {
    // The cached head is the HTTP/1.1 keep-alive one, ready to send.
    buffers_.emplace_back(cached->head.data(), cached->head.size());
  } else {
    head_bytes_.clear();
    AppendStatusLine(head_bytes_, version_, cached->status);
    head_bytes_ += cached->fields();
    QueueHead(keep_alive);
  }
  QueueBody(cached->owned, cached->slices);
  status_ = cached->status;
  cached_ = std::move(cached);
  mesh_ = std::move(mesh);
  StartWrite(keep_alive);
}

void HttpSession::StartWrite(bool keep_alive) {
  deadline_.ExpiresAfter(std::chrono::seconds(ctx_.config().write_timeout_seconds()));
  // Asio hands at most 64 buffers to each sendmsg and continues with the rest.
  net::async_write(socket_, BufferView{buffers_.data(), buffers_.data() + buffers_.size()},
                   beast::bind_front_handler(&HttpSession::OnWrite, shared_from_this(),
                                             !keep_alive));
}

void HttpSession::OnWrite(bool close, beast::error_code ec, size_t bytes) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  ctx_.metrics().RecordRequest(status_, bytes, seconds);
  response_.reset();
  cached_.reset();
  mesh_.reset();
  buffers_.clear();
  if (ec) return Fail(ec, "write");
  if (close || shutting_down_) return DoClose();
  DoRead();
}

void HttpSession::DoClose() {
  beast::error_code ec;
  socket_.shutdown(tcp::socket::shutdown_send, ec);
  if (ec) return;
  // Lingering close: read and drop what the client still sends (the rest
  // of a refused request), because closing with unread bytes makes the
  // kernel send a reset that can destroy our response before the client
  // reads it. Bounded in time and bytes.
  deadline_.ExpiresAfter(kDrainTime);
  DoDrain();
}

void HttpSession::DoDrain() {
  socket_.async_read_some(
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
      ec == http::error::partial_message || ec == net::error::bad_descriptor) {
    return;
  }
  spdlog::debug("http session {}: {}", what, ec.message());
}

}  // namespace meshwave::server
