// A Transport that serves an EncodedStream from memory with the server's
// selection rules, in small odd-sized pieces, and can drop, corrupt or lie
// on demand. Records every packet it sends.
#ifndef MESHWAVE_TESTS_CLIENT_FAKE_TRANSPORT_TESTONLY_H_
#define MESHWAVE_TESTS_CLIENT_FAKE_TRANSPORT_TESTONLY_H_

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/awaitable.hpp>
#include <limits>
#include <memory>
#include <vector>

#include "meshwave/client/transport.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"

namespace meshwave::testing {

struct FakeServerLog {
  std::vector<uint32_t>
      packets_sent;  // ids of every payload sent, whole or not
  int requests = 0;
  uint64_t body_bytes = 0;
};

struct FakeFaults {
  int drops = 0;            // the next `drops` bodies are cut...
  size_t drop_after = 0;    // ...after this many bytes (kIoError)
  int64_t corrupt_at = -1;  // flip this byte of every stream body
  int64_t cursor_skew = 0;  // added to the announced next cursor
};

class FakeTransport final : public client::Transport {
 public:
  FakeTransport(boost::asio::any_io_executor ex, const EncodedStream& stream,
                std::shared_ptr<FakeServerLog> log,
                std::shared_ptr<FakeFaults> faults)
      : ex_(std::move(ex)),
        stream_(stream),
        log_(std::move(log)),
        faults_(std::move(faults)) {}

  boost::asio::any_io_executor executor() override { return ex_; }

  boost::asio::awaitable<Result<std::string>> GetHeader(uint64_t) override {
    ++log_->requests;
    co_return stream_.header.bytes_without_present;
  }

  boost::asio::awaitable<Result<std::string>> GetPacket(uint32_t id) override {
    ++log_->requests;
    if (id >= stream_.packets.size())
      co_return Status(StatusCode::kNotFound, "no packet");
    log_->packets_sent.push_back(id);
    co_return stream_.packets[id];
  }

  boost::asio::awaitable<Status> Stream(const client::StreamRequest& r,
                                        client::StreamSink& sink) override {
    ++log_->requests;
    const auto order = PacketOrder(stream_.header, r.order, r.max_level);
    const Selection s = SelectPackets(
        stream_.header, order,
        r.budget.value_or(std::numeric_limits<uint64_t>::max()), r.from);
    std::string body;
    if (r.from == 0) {
      body = SerializeContainer(stream_, s.ids);
    } else {
      for (uint32_t id : s.ids) body += stream_.packets[id];
    }
    for (uint32_t id : s.ids) log_->packets_sent.push_back(id);
    if (faults_->corrupt_at >= 0 &&
        static_cast<size_t>(faults_->corrupt_at) < body.size()) {
      body[static_cast<size_t>(faults_->corrupt_at)] ^= 0x20;
    }
    client::StreamHead head;
    head.packets = s.ids.size();
    head.next_cursor = static_cast<size_t>(static_cast<int64_t>(s.next_cursor) +
                                           faults_->cursor_skew);
    head.complete = s.next_cursor == order.size();
    head.content_length = body.size();
    if (Status st = sink.OnHead(head); !st.ok()) co_return st;
    size_t limit = body.size();
    bool drop = false;
    if (faults_->drops > 0 && faults_->drop_after < body.size()) {
      --faults_->drops;
      limit = faults_->drop_after;
      drop = true;
    }
    for (size_t pos = 0; pos < limit; pos += 7) {
      const size_t n = std::min<size_t>(7, limit - pos);
      log_->body_bytes += n;
      if (Status st = sink.OnBytes(std::string_view(body).substr(pos, n));
          !st.ok())
        co_return st;
    }
    if (drop) co_return IoError("connection dropped by the fake");
    co_return Status::Ok();
  }

  void Close() override {}

 private:
  boost::asio::any_io_executor ex_;
  const EncodedStream& stream_;
  std::shared_ptr<FakeServerLog> log_;
  std::shared_ptr<FakeFaults> faults_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CLIENT_FAKE_TRANSPORT_TESTONLY_H_
