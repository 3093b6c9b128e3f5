#include "meshwave/client/session.h"

#include <algorithm>
#include <exception>
#include <utility>
#include <optional>

#include "co_status.h"
#include "header_limit.h"
#include "meshwave/container.h"
#include "net.h"
#include "retry.h"
#include "run_to_completion.h"
#include "stream_splitter.h"

namespace meshwave::client {

struct Session::Impl {
  std::unique_ptr<Transport> transport;
  SessionOptions options;
  std::optional<StreamHeader> header;  // `present` cleared
  std::unique_ptr<ProgressiveDecoder> decoder;
  std::vector<uint32_t> order;
  std::vector<std::string> payloads;  // of order[0 .. cursor)
  uint64_t received_bytes = 0;
  size_t packets_received = 0;
  uint64_t budget_bytes = 0;
  int retries = 0;
  ProgressHandler on_progress;

  size_t cursor() const { return payloads.size(); }

  std::span<const uint32_t> Held() const { return {order.data(), cursor()}; }

  Progress MakeProgress() const {
    Progress p;
    p.received_bytes = received_bytes;
    p.packets_received = packets_received;
    p.retries = retries;
    if (!header) return p;
    p.packets = cursor();
    p.order_packets = order.size();
    p.bytes = ContainerSize(*header, Held());
    p.level = decoder->CompleteLevels();
    p.levels = static_cast<int>(header->transform.levels);
    p.estimated_psnr_db = decoder->EstimatedPsnr();
    return p;
  }

  void Report() const {
    if (on_progress) on_progress(MakeProgress(), *decoder);
  }

  Status SetHeader(const StreamHeader& h) {
    auto d = ProgressiveDecoder::Create(h, options.decoder);
    if (!d.ok()) return d.status().WithContext("the server's stream header");
    const int levels = static_cast<int>(h.transform.levels);
    if (options.max_level > levels) {
      return InvalidArgument("max_level " + std::to_string(options.max_level) +
                             " exceeds the " + std::to_string(levels) +
                             " levels of the mesh");
    }
    header = h;
    header->present.clear();
    decoder = std::move(*d);
    order = PacketOrder(*header, options.order, options.max_level);
    payloads.clear();
    Report();
    return Status::Ok();
  }

  Status AddPacket(std::string_view payload, bool report) {
    if (cursor() >= order.size())
      return ParseError("a packet beyond the end of the order");
    const uint32_t id = order[cursor()];
    Status s = decoder->AddPacket(id, payload);
    if (!s.ok()) {
      return s.WithContext("packet " + std::to_string(id) + " (cursor " +
                           std::to_string(cursor()) + ")");
    }
    payloads.emplace_back(payload);
    if (report) {
      ++packets_received;
      Report();
    }
    return Status::Ok();
  }

  // Payload bytes of order[from .. to).
  uint64_t PayloadBytes(size_t from, size_t to) const {
    uint64_t n = 0;
    for (size_t i = from; i < to; ++i) n += PacketLength(*header, order[i]);
    return n;
  }

  net::awaitable<Result<bool>> Step(const Budget& budget);
  net::awaitable<Status> StreamFrom(const Budget& budget, size_t target);

  class ResponseSink;
};

// Consumes one /stream response: checks its head against what the client
// computed from the header, and feeds each packet to the session.
class Session::Impl::ResponseSink final : public StreamSink,
                                          public StreamSplitter::Events {
 public:
  ResponseSink(Session::Impl& s, const Budget& budget,
               std::optional<size_t> target)
      : s_(s),
        budget_(budget),
        target_(target),
        splitter_(!s.header, s.options.max_header_bytes, *this) {}

  Status OnHead(const StreamHead& head) override {
    head_ = head;
    return target_ ? CheckHead() : Status::Ok();
  }
  Status OnBytes(std::string_view bytes) override {
    s_.received_bytes += bytes.size();
    return splitter_.Feed(bytes);
  }
  Status OnHeader(const StreamHeader& received) override {
    MW_RETURN_IF_ERROR(s_.SetHeader(received));
    target_ = TargetCursor(*s_.header, s_.order, budget_);
    return CheckHead();
  }
  std::optional<uint64_t> NextPacketLength() override {
    if (!target_ || s_.cursor() >= *target_) return std::nullopt;
    return PacketLength(*s_.header, s_.order[s_.cursor()]);
  }
  Status OnPacket(std::string_view payload) override {
    return s_.AddPacket(payload, true);
  }

  // A message transport: the header and packets come whole, each packet
  // with its position and id, which must be the ones the client expects.
  Status OnHeaderMessage(std::string_view bytes) override {
    messages_ = true;
    if (s_.header) return ParseError("the server sent the header again");
    s_.received_bytes += bytes.size();
    MW_RETURN_IF_ERROR(
        CheckHeaderLength(bytes.size(), s_.options.max_header_bytes));
    auto parsed = ReadStreamHeader(bytes);
    if (!parsed.ok()) return ParseError("the server's stream header does not parse");
    return OnHeader(*parsed);
  }
  Status OnPacketMessage(size_t cursor, uint32_t id,
                         std::string_view payload) override {
    messages_ = true;
    s_.received_bytes += payload.size();
    if (!s_.header) return ParseError("a packet before the stream header");
    if (!target_ || s_.cursor() >= *target_) {
      return ParseError("a packet beyond the end of the selection");
    }
    if (cursor != s_.cursor() || id != s_.order[s_.cursor()]) {
      return ParseError("the server sent packet " + std::to_string(id) +
                        " at cursor " + std::to_string(cursor) +
                        ", expected packet " +
                        std::to_string(s_.order[s_.cursor()]) + " at cursor " +
                        std::to_string(s_.cursor()));
    }
    return s_.AddPacket(payload, true);
  }

  Status Finish() const {
    if (!messages_) MW_RETURN_IF_ERROR(splitter_.Finish());
    if (!target_) return ParseError("the stream ended before its header");
    if (s_.cursor() != *target_) {
      return ParseError("the response ended at cursor " +
                        std::to_string(s_.cursor()) + ", expected " +
                        std::to_string(*target_));
    }
    return Status::Ok();
  }

 private:
  // The server selects with the same rules as the client (SelectPackets on
  // the same order): any difference means a server we do not understand.
  Status CheckHead() const {
    if (head_.next_cursor != *target_) {
      return ParseError("the server sent packets up to cursor " +
                        std::to_string(head_.next_cursor) + ", expected " +
                        std::to_string(*target_) +
                        " (client and server disagree on the order)");
    }
    const size_t from = std::min(first_cursor_, *target_);
    const uint64_t expected =
        with_header_ ? ContainerSize(*s_.header, {s_.order.data(), *target_})
                     : s_.PayloadBytes(from, *target_);
    if (head_.content_length && *head_.content_length != expected) {
      return ParseError("the response holds " +
                        std::to_string(*head_.content_length) +
                        " bytes, expected " + std::to_string(expected));
    }
    return Status::Ok();
  }

  Session::Impl& s_;
  Budget budget_;
  std::optional<size_t> target_;
  size_t first_cursor_ = s_.header ? s_.cursor() : 0;
  bool with_header_ = !s_.header;  // the response starts with the header
  StreamHead head_;
  StreamSplitter splitter_;
  bool messages_ = false;  // fed by OnHeaderMessage/OnPacketMessage
};

net::awaitable<Status> Session::Impl::StreamFrom(const Budget& budget,
                                                 size_t target) {
  StreamRequest request;
  request.order = options.order;
  request.max_level = options.max_level;
  request.from = header ? cursor() : 0;
  request.header_held = header.has_value();
  request.max_header_bytes = options.max_header_bytes;
  if (header) {
    // Exactly the payloads of order[cursor .. target): the server's budget
    // from a cursor counts payloads only.
    request.budget = PayloadBytes(cursor(), target);
  } else if (budget.kind == Budget::Kind::kBytes) {
    request.budget = budget.bytes;
  }
  ResponseSink sink(*this, budget,
                    header ? std::optional<size_t>(target) : std::nullopt);
  MWC_CO_RETURN_IF_ERROR(co_await transport->Stream(request, sink));
  co_return sink.Finish();
}

// One request; true when the budget is reached.
net::awaitable<Result<bool>> Session::Impl::Step(const Budget& budget) {
  if (!header) {
    if (budget.kind != Budget::Kind::kPsnr) {
      // The first /stream response carries the header: one round trip.
      MWC_CO_RETURN_IF_ERROR(co_await StreamFrom(budget, 0));
      co_return false;
    }
    // A PSNR target needs the index before choosing the packets.
    auto bytes = co_await transport->GetHeader(options.max_header_bytes);
    if (!bytes.ok()) co_return bytes.status();
    received_bytes += bytes->size();
    MWC_CO_RETURN_IF_ERROR(
        CheckHeaderLength(bytes->size(), options.max_header_bytes));
    auto h = ReadStreamHeader(*bytes);
    if (!h.ok()) co_return ParseError("the server's stream header does not parse");
    MWC_CO_RETURN_IF_ERROR(SetHeader(*h));
    co_return false;
  }
  const size_t target = TargetCursor(*header, order, budget);
  if (cursor() >= target) co_return true;
  if (cursor() == 0 && !transport->CanStreamPayloadsFromStart()) {
    // /stream?from=0 would send the header again: the first packet by id.
    auto payload = co_await transport->GetPacket(order[0]);
    if (!payload.ok()) co_return payload.status();
    received_bytes += payload->size();
    MWC_CO_RETURN_IF_ERROR(AddPacket(*payload, true));
    co_return false;
  }
  MWC_CO_RETURN_IF_ERROR(co_await StreamFrom(budget, target));
  co_return false;
}

Session::Session(std::unique_ptr<Transport> transport,
                 const SessionOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->transport = std::move(transport);
  impl_->options = options;
}

Session::~Session() = default;

Status Session::Restore(std::string_view container, uint64_t budget_bytes) {
  auto parsed = ParseContainer(container);
  if (!parsed.ok()) return parsed.status();
  Impl& s = *impl_;
  s.on_progress = nullptr;
  Status status = s.SetHeader(parsed->header);
  if (status.ok() &&
      (parsed->ids.size() > s.order.size() ||
       !std::equal(parsed->ids.begin(), parsed->ids.end(), s.order.begin()))) {
    status = ParseError(
        std::string("the container's packets are not a prefix of the ") +
        ProgressionName(s.options.order) + " order");
  }
  for (size_t i = 0; status.ok() && i < parsed->ids.size(); ++i) {
    status = s.AddPacket(parsed->payloads[i], false);
  }
  if (!status.ok()) {
    s.header.reset();
    s.decoder.reset();
    s.order.clear();
    s.payloads.clear();
    return status;
  }
  s.budget_bytes = std::max(budget_bytes, ContainerSize(*s.header, s.Held()));
  return Status::Ok();
}

net::awaitable<Status> Session::Fetch(Budget budget,
                                      ProgressHandler on_progress) {
  Impl& s = *impl_;
  s.on_progress = std::move(on_progress);
  Status status = co_await RetryWithBackoff(
      s.transport->executor(), s.options.retry, s.retries,
      [&s, &budget] { return s.Step(budget); },
      [&s] { return std::make_pair(s.cursor(), s.header.has_value()); });
  if (!status.ok()) {
    if (status.code() != StatusCode::kIoError) s.transport->Close();
    co_return status;
  }
  if (s.header) {
    const uint64_t reached = ContainerSize(*s.header, s.Held());
    const uint64_t asked =
        budget.kind == Budget::Kind::kBytes ? budget.bytes : reached;
    s.budget_bytes = std::max({s.budget_bytes, asked, reached});
  }
  co_return Status::Ok();
}

void Session::AsyncFetch(Budget budget, ProgressHandler on_progress,
                         std::function<void(Status)> done) {
  net::co_spawn(impl_->transport->executor(),
                Fetch(budget, std::move(on_progress)),
                [done = std::move(done)](std::exception_ptr e, Status s) {
                  // Only allocation failures and bugs throw: report, do not
                  // crash.
                  if (done) done(StatusOf(e, std::move(s)));
                });
}

bool Session::has_header() const { return impl_->header.has_value(); }
const ProgressiveDecoder* Session::decoder() const {
  return impl_->decoder.get();
}
const SessionOptions& Session::options() const { return impl_->options; }
Progress Session::progress() const { return impl_->MakeProgress(); }
uint64_t Session::budget_bytes() const { return impl_->budget_bytes; }

std::string Session::Container() const {
  const Impl& s = *impl_;
  if (!s.header) return {};
  std::string out = SerializeContainerHead(*s.header, s.Held());
  for (const auto& p : s.payloads) out += p;
  return out;
}

}  // namespace meshwave::client
