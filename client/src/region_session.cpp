#include "meshwave/client/region_session.h"

#include <map>
#include <utility>
#include <vector>

#include "co_status.h"
#include "header_limit.h"
#include "meshwave/container.h"
#include "meshwave/held_units.h"
#include "meshwave/stream_units.h"
#include "net.h"
#include "retry.h"
#include "run_to_completion.h"
#include "meshwave/packet_parts.h"

namespace meshwave::client {

struct RegionSession::Impl : UnitSink {
  std::unique_ptr<net::io_context> io;  // the URL constructor's; outlives the transport
  std::unique_ptr<Transport> transport;
  SessionOptions options;
  std::optional<StreamHeader> header;  // `present` cleared
  // Holds the units received and the rules of what each needs
  // (decoder->held()).
  std::unique_ptr<ProgressiveDecoder> decoder;
  std::optional<UnitNumbering> numbering;
  // What arrived, by (packet id, part or StreamUnit::kWholePacket).
  std::map<std::pair<uint32_t, uint32_t>, std::string> payloads;
  size_t units_held = 0;
  uint64_t payload_bytes = 0;
  uint64_t received_bytes = 0;
  size_t units_received = 0;
  int retries = 0;
  std::optional<uint64_t> remaining;  // of the running fetch's budget
  bool report = false;
  ProgressHandler on_progress;

  Progress MakeProgress() const {
    Progress p;
    p.received_bytes = received_bytes;
    p.packets_received = units_received;
    p.retries = retries;
    if (!header) return p;
    p.packets = units_held;
    p.order_packets = numbering->size();
    p.bytes = ContainerSize(*header, {}) + payload_bytes;
    p.level = decoder->CompleteLevels();
    p.levels = static_cast<int>(header->transform.levels);
    p.estimated_psnr_db = decoder->EstimatedPsnr();
    return p;
  }
  void Report() const {
    if (report && on_progress) on_progress(MakeProgress(), *decoder);
  }

  void Clear() {
    header.reset();
    decoder.reset();
    numbering.reset();
    payloads.clear();
    units_held = 0;
    payload_bytes = 0;
  }

  Status SetHeader(const StreamHeader& h) {
    auto d = ProgressiveDecoder::Create(h, options.decoder);
    if (!d.ok()) return d.status().WithContext("the server's stream header");
    if (options.max_level > static_cast<int>(h.transform.levels)) {
      return InvalidArgument("max_level " + std::to_string(options.max_level) + " exceeds the " +
                             std::to_string(h.transform.levels) + " levels of the mesh");
    }
    header = h;
    header->present.clear();
    decoder = std::move(*d);
    numbering.emplace(decoder->held());
    Report();
    return Status::Ok();
  }

  // A unit from the server, or restored: checked against what is held
  // (never twice, never before what it needs), then decoded.
  Status OnUnit(StreamUnit u, std::string_view payload) override {
    if (!header) return ParseError("a unit before the stream header");
    const HeldUnits& held = decoder->held();
    const std::string what = u.whole() ? "packet " + std::to_string(u.id)
                                       : "part " + std::to_string(u.part) + " of packet " +
                                             std::to_string(u.id);
    if (!held.Valid(u)) return ParseError("the server sent " + what + ", not in the stream");
    if (held.Has(u)) return ParseError("the server sent " + what + " again");
    if (!held.Ready(u)) return ParseError("the server sent " + what + " before what it needs");
    if (remaining && payload.size() > *remaining) {
      return ParseError("the server sent more than the budget");
    }
    Status s = u.whole() ? decoder->AddPacket(u.id, payload)
                         : decoder->AddPacketPart(u.id, u.part, payload);
    if (!s.ok()) return s.WithContext(what);
    const uint32_t parts = held.PartCount(u.id);
    units_held += u.whole() && parts > 0 ? parts : 1;
    payloads[{u.id, u.part}] = std::string(payload);
    payload_bytes += payload.size();
    if (remaining) *remaining -= payload.size();
    if (report) {
      received_bytes += payload.size();
      ++units_received;
      Report();
    }
    return Status::Ok();
  }

  net::awaitable<Status> GetHeader() {
    auto bytes = co_await transport->GetHeader(options.max_header_bytes);
    if (!bytes.ok()) co_return bytes.status();
    received_bytes += bytes->size();
    MWC_CO_RETURN_IF_ERROR(CheckHeaderLength(bytes->size(), options.max_header_bytes));
    auto h = ReadStreamHeader(*bytes);
    if (!h.ok()) co_return ParseError("the server's stream header does not parse");
    co_return SetHeader(*h);
  }

  // The whole payload of packet `id` held whole (received so, or every
  // part of it).
  std::string WholePayload(uint32_t id) const {
    if (auto it = payloads.find({id, StreamUnit::kWholePacket}); it != payloads.end()) {
      return it->second;
    }
    std::vector<std::string> parts;
    for (uint32_t p = 0; p < decoder->PartCount(id); ++p) parts.push_back(payloads.at({id, p}));
    return JoinPacketParts(parts);
  }
};

RegionSession::RegionSession(std::unique_ptr<Transport> transport, const SessionOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->transport = std::move(transport);
  impl_->options = options;
}

RegionSession::RegionSession(const MeshUrl& url, const SessionOptions& options,
                             const TransportOptions& transport_options)
    : impl_(std::make_unique<Impl>()) {
  impl_->io = std::make_unique<net::io_context>(1);
  impl_->transport = MakeTransport(impl_->io->get_executor(), url, transport_options);
  impl_->options = options;
}

RegionSession::~RegionSession() {
  if (impl_) impl_->transport.reset();  // its sockets before their io_context
}

net::awaitable<Status> RegionSession::Fetch(std::optional<Region> region,
                                            std::optional<uint64_t> budget,
                                            bool budget_counts_header,
                                            ProgressHandler on_progress) {
  Impl& s = *impl_;
  s.on_progress = std::move(on_progress);
  s.report = true;
  s.remaining = budget;
  bool header_paid = !budget_counts_header || !budget;
  // One try: the header if it is not held, else the units.
  auto step = [&]() -> net::awaitable<Result<bool>> {
    if (!s.header) {
      MWC_CO_RETURN_IF_ERROR(co_await s.GetHeader());
      co_return false;
    }
    if (!header_paid) {
      const uint64_t header = ContainerSize(*s.header, {});
      if (*s.remaining < header) {
        co_return InvalidArgument("budget " + std::to_string(*s.remaining) +
                                  " is smaller than the stream header (" +
                                  std::to_string(header) + " bytes)");
      }
      *s.remaining -= header;
      header_paid = true;
    }
    UnitStreamRequest request;
    request.region = region;
    request.order = s.options.order;
    request.max_level = s.options.max_level;
    request.held = EncodeHeldUnits(s.decoder->held(), *s.numbering);
    request.budget = s.remaining;
    MWC_CO_RETURN_IF_ERROR(co_await s.transport->StreamUnits(request, s));
    co_return true;
  };
  const Status status = co_await RetryWithBackoff(
      s.transport->executor(), s.options.retry, s.retries, step,
      [&s] { return std::make_pair(s.units_held, s.header.has_value()); });
  s.report = false;
  if (!status.ok()) {
    if (status.code() != StatusCode::kIoError) s.transport->Close();
    co_return status;
  }
  s.remaining.reset();
  co_return Status::Ok();
}

Status RegionSession::FetchBlocking(std::optional<Region> region,
                                    std::optional<uint64_t> budget, bool budget_counts_header,
                                    const ProgressHandler& on_progress) {
  if (!impl_->io) return InvalidArgument("FetchBlocking needs the URL constructor");
  return RunToCompletion(*impl_->io,
                         Fetch(std::move(region), budget, budget_counts_header, on_progress));
}

Status RegionSession::Restore(std::string_view container, std::string_view parts) {
  Impl& s = *impl_;
  s.Clear();
  s.report = false;
  auto parsed = ParseContainer(container);
  if (!parsed.ok()) return parsed.status();
  Status status = s.SetHeader(parsed->header);
  for (size_t i = 0; status.ok() && i < parsed->ids.size(); ++i) {
    status = s.OnUnit({parsed->ids[i]}, parsed->payloads[i]);
  }
  if (status.ok()) {
    UnitRecordReader reader(uint64_t{1} << 30,
                            [&s](StreamUnit u, std::string_view p) { return s.OnUnit(u, p); });
    status = reader.Feed(parts);
    if (status.ok() && !reader.at_boundary()) status = ParseError("the parts end inside a unit");
  }
  if (!status.ok()) s.Clear();
  return status;
}

bool RegionSession::has_header() const { return impl_->header.has_value(); }
const ProgressiveDecoder* RegionSession::decoder() const { return impl_->decoder.get(); }
const SessionOptions& RegionSession::options() const { return impl_->options; }
Progress RegionSession::progress() const { return impl_->MakeProgress(); }
uint64_t RegionSession::header_bytes() const {
  return impl_->header ? ContainerSize(*impl_->header, {}) : 0;
}
std::string RegionSession::HeldText() const {
  return impl_->header ? EncodeHeldUnits(impl_->decoder->held(), *impl_->numbering)
                       : std::string();
}

std::string RegionSession::Container() const {
  const Impl& s = *impl_;
  if (!s.header) return {};
  // A packet held whole has every packet it needs held whole (a packet
  // needs all of a split dependency's parts): these form a valid container.
  std::vector<uint32_t> ids;
  std::string payloads;
  const HeldUnits& held = s.decoder->held();
  for (uint32_t id = 0; id < held.packet_count(); ++id) {
    if (!held.Has({id})) continue;
    ids.push_back(id);
    payloads += s.WholePayload(id);
  }
  return SerializeContainerHead(*s.header, ids) + payloads;
}

std::string RegionSession::Parts() const {
  const Impl& s = *impl_;
  std::string out;
  if (!s.header) return out;
  // Unit numbers follow the packet ids: each part after what it needs.
  for (size_t n = 0; n < s.numbering->size(); ++n) {
    const StreamUnit u = s.numbering->unit(n);
    if (u.whole() || s.decoder->HasPacket(u.id) || !s.decoder->held().Has(u)) continue;
    AppendUnitRecord(out, u, s.payloads.at({u.id, u.part}));
  }
  return out;
}

}  // namespace meshwave::client
