// Fuzz target: the ProgressiveDecoder fed the fixture's real packets in an
// arbitrary order, with repeats, unknown ids and damaged payloads. Each
// input byte is one step: the low 7 bits pick a packet id (some past the
// index), the high bit damages the payload (one byte flipped or cut).
// Invariants: a real packet whose dependencies are met always decodes;
// refused packets change nothing; once every packet is in, the positions
// equal those of the canonical order exactly.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz_fixture_testonly.h"
#include "meshwave/progressive_decoder.h"

using namespace meshwave;

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
  ProgressiveDecoder& dec = *decoder;
  dec.Reset();
  fuzz::Require(dec.packets_decoded() == 0, "Reset forgets every packet");
  size_t added = 0;
  for (size_t i = 0; i < size; ++i) {
    const uint32_t id = (data[i] & 0x7f) % (n + 4);  // a few ids past the index
    if (id >= n) {
      fuzz::Require(!dec.AddPacket(id, "x").ok(), "an unknown id is refused");
      continue;
    }
    std::string payload = f.payloads[id];
    const bool damage = (data[i] & 0x80) != 0 && !payload.empty();  // empty payloads exist
    if (damage) {
      if (i % 2 == 0) {
        payload[(i * 131) % payload.size()] ^= static_cast<char>(1 + i % 255);
      } else {
        payload.pop_back();
      }
    }
    const bool was_there = dec.HasPacket(id);
    const bool deps = dec.DependenciesMet(id);
    const Status s = dec.AddPacket(id, payload);
    if (!damage && !was_there && deps) {
      fuzz::Require(s.ok(), "a real packet whose dependencies are met decodes");
    }
    if (was_there || !deps || damage) {
      fuzz::Require(!s.ok(), "a repeated, early or damaged packet is refused");
    }
    if (s.ok()) ++added;
    fuzz::Require(dec.packets_decoded() == added, "packets_decoded counts what was added");
  }
  // The mesh once per input, not every few steps: the inverse transform
  // was 40% of an execution (perf), and the decoder's state is what the
  // order exercises. The level comes from the last step.
  if (added == n) {
    fuzz::Require(dec.Positions() == f.full, "every order gives the same final mesh");
  } else if (size > 0) {
    (void)dec.Positions(static_cast<int>(data[size - 1] % 5) - 1);
  }
  return 0;
}
