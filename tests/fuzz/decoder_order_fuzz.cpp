// Fuzz target: the ProgressiveDecoder fed the fixture's real packets, and
// the precinct parts of its split packets, in an arbitrary order, with
// repeats, unknown ids and damaged payloads. Each input byte is one step:
// the low 7 bits pick a unit (a whole packet, one part of a split packet,
// or an id past the index), the high bit damages it (one byte flipped or
// cut). Invariants: a real unit whose dependencies are met always decodes;
// refused units change nothing; a packet is held once all its parts are;
// once every packet is in, the positions equal those of the canonical
// order exactly. A damaged part has no check of its own (the index checks
// whole packets), so once one is offered the input only has to be
// survived.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_fixture_testonly.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/packet_parts.h"

using namespace meshwave;

namespace {

struct Unit {
  uint32_t id;
  int64_t part;  // -1: the whole packet
  std::string payload;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::Fixture& f = fuzz::GetFixture();
  const uint32_t n = static_cast<uint32_t>(f.payloads.size());
  // One decoder per process, reset per input: Create was 40 % of an
  // execution, and Reset must leave no trace of the previous input (the
  // invariants below would catch one).
  static const std::unique_ptr<ProgressiveDecoder> decoder = [&] {
    auto created = ProgressiveDecoder::Create(f.header);
    fuzz::Require(created.ok(), "the fixture header is valid");
    return std::move(created).value();
  }();
  static const std::vector<Unit> units = [&] {
    std::vector<Unit> out;
    for (uint32_t id = 0; id < n; ++id) {
      out.push_back({id, -1, f.payloads[id]});
      const uint32_t count = decoder->PartCount(id);
      if (count == 0) continue;
      auto parts = SplitPacketParts(f.payloads[id], count);
      fuzz::Require(parts.ok(), "the fixture's split packets split");
      for (uint32_t p = 0; p < count; ++p) out.push_back({id, p, std::string((*parts)[p])});
    }
    fuzz::Require(out.size() > n, "the fixture has split packets");
    return out;
  }();
  ProgressiveDecoder& dec = *decoder;
  dec.Reset();
  fuzz::Require(dec.packets_decoded() == 0, "Reset forgets every packet");
  const uint32_t u = static_cast<uint32_t>(units.size());
  bool damaged_part = false;
  for (size_t i = 0; i < size; ++i) {
    const uint32_t pick = (data[i] & 0x7f) % (u + 4);  // a few ids past the index
    if (pick >= u) {
      const uint32_t id = n + pick - u;
      fuzz::Require(!dec.AddPacket(id, "x").ok(), "an unknown id is refused");
      fuzz::Require(!dec.AddPacketPart(id, 0, "x").ok(), "an unknown id's part is refused");
      continue;
    }
    const Unit& unit = units[pick];
    std::string payload = unit.payload;
    const bool damage = (data[i] & 0x80) != 0 && !payload.empty();  // empty payloads exist
    if (damage) {
      if (i % 2 == 0) {
        payload[(i * 131) % payload.size()] ^= static_cast<char>(1 + i % 255);
      } else {
        payload.pop_back();
      }
    }
    bool was_there = false, deps = false;
    Status s;
    if (unit.part < 0) {
      was_there = dec.HasPacket(unit.id);
      deps = dec.DependenciesMet(unit.id);
      s = dec.AddPacket(unit.id, payload);
    } else {
      const auto p = static_cast<uint32_t>(unit.part);
      was_there = dec.HasPart(unit.id, p);
      deps = dec.PartDependenciesMet(unit.id, p);
      damaged_part = damaged_part || (damage && !was_there && deps);
      s = dec.AddPacketPart(unit.id, p, payload);
    }
    if (!damage && !was_there && deps && !damaged_part) {
      fuzz::Require(s.ok(), "a real unit whose dependencies are met decodes");
    }
    if (was_there || !deps || (damage && unit.part < 0)) {
      fuzz::Require(!s.ok(), "a repeated, early or damaged packet is refused");
    }
    size_t held = 0;
    for (uint32_t id = 0; id < n; ++id) held += dec.HasPacket(id);
    fuzz::Require(dec.packets_decoded() == held, "packets_decoded counts the packets held");
  }
  // The mesh once per input, not every few steps: the inverse transform
  // was 40% of an execution (perf), and the decoder's state is what the
  // order exercises. The level comes from the last step.
  if (dec.packets_decoded() == n && !damaged_part) {
    fuzz::Require(dec.Positions() == f.full, "every order gives the same final mesh");
  } else if (size > 0) {
    (void)dec.Positions(static_cast<int>(data[size - 1] % 5) - 1);
  }
  return 0;
}
