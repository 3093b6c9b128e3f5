// Fuzz target: the units' wire forms a server or client reads from the
// other side (meshwave/stream_units.h), over the fixture's stream (split
// packets). Byte 0 picks: even, the rest is a held bitmap's text — one that
// is accepted must be closed under the dependencies and encode back to a
// text naming the same set; odd, the rest is a unit-records body, fed in
// pieces whose sizes byte 0 sets — the records read must be the same
// whatever the pieces, each a unit of the stream no longer than its packet.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fuzz_fixture_testonly.h"
#include "meshwave/region_order.h"
#include "meshwave/stream_units.h"

using namespace meshwave;

namespace {

struct Units {
  StreamPrecincts precincts;
  HeldUnits empty;
  UnitNumbering numbering;
  explicit Units(StreamPrecincts p)
      : precincts(std::move(p)), empty(fuzz::GetFixture().header, precincts.parents()), numbering(empty) {}
};

const Units& GetUnits() {
  static const Units* u = [] {
    auto p = StreamPrecincts::Create(fuzz::GetFixture().header);
    fuzz::Require(p.ok(), "the fixture has precincts");
    return new Units(std::move(p).value());
  }();
  return *u;
}

using Records = std::vector<std::pair<StreamUnit, std::string>>;

Status ReadAll(std::string_view body, size_t piece, Records& out) {
  const fuzz::Fixture& f = fuzz::GetFixture();
  const Units& u = GetUnits();
  UnitRecordReader reader(1 << 16, [&](StreamUnit unit, std::string_view payload) {
    if (!u.empty.Valid(unit)) return InvalidArgument("no such unit");
    fuzz::Require(payload.size() <= (1 << 16), "a payload within the reader's limit");
    if (payload.size() > f.payloads[unit.id].size()) return InvalidArgument("too long");
    out.emplace_back(unit, std::string(payload));
    return Status::Ok();
  });
  for (size_t at = 0; at < body.size(); at += piece) {
    MW_RETURN_IF_ERROR(reader.Feed(body.substr(at, piece)));
  }
  fuzz::Require(reader.records() == out.size(), "records counts what was handed on");
  return Status::Ok();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const Units& u = GetUnits();
  const std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) {
    HeldUnits held = u.empty;
    if (!DecodeHeldUnits(rest, u.numbering, held).ok()) return 0;
    // Closed: replaying the held units in number order, each is ready.
    HeldUnits replay = u.empty;
    for (size_t n = 0; n < u.numbering.size(); ++n) {
      const StreamUnit unit = u.numbering.unit(n);
      if (!held.Has(unit)) continue;
      fuzz::Require(replay.Ready(unit), "an accepted held set is closed");
      replay.Add(unit);
    }
    HeldUnits again = u.empty;
    fuzz::Require(DecodeHeldUnits(EncodeHeldUnits(held, u.numbering), u.numbering, again).ok(),
                  "an encoded held set decodes");
    for (size_t n = 0; n < u.numbering.size(); ++n) {
      fuzz::Require(again.Has(u.numbering.unit(n)) == held.Has(u.numbering.unit(n)),
                    "the held set round-trips");
    }
    return 0;
  }
  Records whole, pieces;
  const Status a = ReadAll(rest, rest.size() + 1, whole);
  const Status b = ReadAll(rest, 1 + data[0] / 2 % 16, pieces);
  fuzz::Require(a.ok() == b.ok(), "the same verdict whatever the pieces");
  fuzz::Require(whole == pieces, "the same records whatever the pieces");
  return 0;
}
