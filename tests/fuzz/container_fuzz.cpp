// Fuzz target: the container parser and everything a client does with an
// untrusted header before any payload: ParseContainer (whole and cut
// short), ValidateStreamHeader, the three packet orders, budget selection,
// the PSNR curve, ProgressiveDecoder::Create and the payloads that came
// with the header.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"

using namespace meshwave;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto strict = ParseContainer(bytes, false);
  auto parsed = ParseContainer(bytes, true);
  fuzz::Require(!strict.ok() || parsed.ok(), "a whole container also parses as truncated");
  if (!parsed.ok()) return 0;
  fuzz::Require(parsed->ids.size() == parsed->payloads.size(), "one payload per id");
  const StreamHeader& h = parsed->header;
  if (!ValidateStreamHeader(h).ok()) return 0;
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    const std::vector<uint32_t> order = PacketOrder(h, p);
    fuzz::Require(order.size() == h.packets.length.size(),
                  "an order holds every packet");
    const Selection s = SelectPackets(h, order, size * 2);
    fuzz::Require(s.next_cursor <= order.size(), "the cursor stays in the order");
    (void)EstimatedPsnrCurve(h, order);
    if (!order.empty()) (void)PacketDependencies(h, order.back());
  }
  // Keep the decoder's meshes small (the seeds have 512 faces) so that a
  // header asking for a huge one is refused cheaply rather than run out of
  // the fuzzer's memory or time; the limits' own checks are what that tests.
  DecoderOptions options;
  options.max_base_vertices = 1u << 12;
  options.max_faces = 1u << 14;
  options.threads = 1;  // the set-up on first use: no threads started per input
  auto dec = ProgressiveDecoder::Create(h, options);
  if (!dec.ok()) return 0;
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    (void)(*dec)->AddPacket(parsed->ids[i], parsed->payloads[i]);
  }
  (void)(*dec)->EstimatedPsnr();
  (void)(*dec)->CompleteLevels();
  (void)(*dec)->DetailLevels();
  (void)(*dec)->Mesh();
  return 0;
}
