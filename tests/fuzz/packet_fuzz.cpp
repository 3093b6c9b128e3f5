// Fuzz target: the packet decoder on arbitrary payload bytes. The header is
// the fixture's, with the chosen packet's length and check rewritten to
// match the input so that the bytes reach the bitplane decoder (a corrupt
// payload with a valid check: what a malicious server can send). Byte 0 picks
// the packet; the packets before it in index order (a dependency-closed
// prefix) are the real ones, and the real packets after it are added
// afterwards: each must be decoded or refused, never crash. A base
// refinement packet's length is fixed by the header (3 bits per base
// vertex), so its bytes are cut or zero-padded to that length.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "meshwave/progressive_decoder.h"
#include "stream/packet_index.h"

using namespace meshwave;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const fuzz::Fixture& f = fuzz::GetFixture();
  const uint32_t n = static_cast<uint32_t>(f.payloads.size());
  const uint32_t id = data[0] % n;
  std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  StreamHeader h = f.header;
  if (PacketLayout(h).IsBase(id)) bytes.resize(h.packets.length[id], '\0');
  const std::string_view payload = bytes;
  h.packets.length[id] = static_cast<uint32_t>(payload.size());
  const uint16_t check = PacketCheck(payload);
  h.packets.check[2 * id] = static_cast<char>(check >> 8);
  h.packets.check[2 * id + 1] = static_cast<char>(check & 0xff);
  DecoderOptions options;
  options.threads = 1;  // the set-up on first use: no threads started per input
  auto dec = ProgressiveDecoder::Create(h, options);
  fuzz::Require(dec.ok(), "the fixture header is valid");
  for (uint32_t k = 0; k < id; ++k) {
    fuzz::Require((*dec)->AddPacket(k, f.payloads[k]).ok(), "a real prefix decodes");
  }
  const Status s = (*dec)->AddPacket(id, payload);
  fuzz::Require(s.ok() == (*dec)->HasPacket(id), "HasPacket follows AddPacket");
  for (uint32_t k = id + 1; k < n; ++k) (void)(*dec)->AddPacket(k, f.payloads[k]);
  (void)(*dec)->EstimatedPsnr();
  (void)(*dec)->CompleteLevels();
  (void)(*dec)->DetailLevels();
  const TriMesh mesh = (*dec)->Mesh();
  fuzz::Require(mesh.positions.size() == f.full.size(), "the mesh keeps its vertex count");
  return 0;
}
