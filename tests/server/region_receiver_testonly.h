// What a client of region requests keeps (docs/API.md, "Region requests"),
// for the server tests: a decoder fed every unit as it arrives, and the
// units it holds (its held()). Refuses a unit sent twice or before what it
// needs.
#ifndef MESHWAVE_TESTS_SERVER_REGION_RECEIVER_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_REGION_RECEIVER_TESTONLY_H_

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/progressive_decoder.h"
#include "meshwave/stream_header.h"
#include "meshwave/stream_units.h"

namespace meshwave::testing {

class RegionReceiver {
 public:
  // `header`: GET /header's bytes (or StreamStart.header).
  explicit RegionReceiver(std::string_view header) {
    auto h = ReadStreamHeader(header);
    EXPECT_TRUE(h.ok()) << h.status().ToString();
    header_ = *std::move(h);
    auto d = ProgressiveDecoder::Create(header_);
    EXPECT_TRUE(d.ok()) << d.status().ToString();
    decoder_ = std::move(d).value();
    numbering_.emplace(decoder_->held());
  }

  Status Receive(StreamUnit u, std::string_view payload) {
    const HeldUnits& held = decoder_->held();
    if (!held.Valid(u)) return InvalidArgument("no such unit");
    if (held.Has(u)) return InvalidArgument("unit sent twice: packet " + std::to_string(u.id));
    if (!held.Ready(u)) return InvalidArgument("unit before what it needs");
    MW_RETURN_IF_ERROR(u.whole() ? decoder_->AddPacket(u.id, payload)
                                 : decoder_->AddPacketPart(u.id, u.part, payload));
    ++units_;
    parts_ += !u.whole();
    return Status::Ok();
  }
  // Every record of a unit-records body.
  Status ReceiveBody(std::string_view body) {
    UnitRecordReader reader(uint64_t{1} << 32,
                            [this](StreamUnit u, std::string_view p) { return Receive(u, p); });
    MW_RETURN_IF_ERROR(reader.Feed(body));
    if (!reader.at_boundary()) return ParseError("body ends inside a record");
    return Status::Ok();
  }

  std::string Held() const { return EncodeHeldUnits(decoder_->held(), *numbering_); }
  bool AllHeld() const {
    for (size_t n = 0; n < numbering_->size(); ++n) {
      if (!decoder_->held().Has(numbering_->unit(n))) return false;
    }
    return true;
  }
  const StreamHeader& header() const { return header_; }
  const HeldUnits& held() const { return decoder_->held(); }
  const UnitNumbering& numbering() const { return *numbering_; }
  ProgressiveDecoder& decoder() { return *decoder_; }
  size_t units() const { return units_; }
  size_t parts() const { return parts_; }

 private:
  StreamHeader header_;
  std::optional<UnitNumbering> numbering_;
  std::unique_ptr<ProgressiveDecoder> decoder_;
  size_t units_ = 0;
  size_t parts_ = 0;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_REGION_RECEIVER_TESTONLY_H_
