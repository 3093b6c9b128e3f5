// decode_example IN.mwv BYTES OUT.ply: decodes the prefix of a stream that
// fits BYTES (the quality order) with the decoder library alone
// (meshwave::decoder: no protobuf, no networking) and writes the mesh.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: decode_example IN.mwv BYTES OUT.ply\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string container = bytes.str();
  auto parsed = meshwave::ParseContainer(container);
  if (!parsed.ok()) {
    std::fprintf(stderr, "%s\n", parsed.status().ToString().c_str());
    return 1;
  }
  auto decoder = meshwave::ProgressiveDecoder::Create(parsed->header);
  if (!decoder.ok()) {
    std::fprintf(stderr, "%s\n", decoder.status().ToString().c_str());
    return 1;
  }
  const auto order = meshwave::PacketOrder(parsed->header, meshwave::Progression::kQuality);
  const auto selection =
      meshwave::SelectPackets(parsed->header, order, std::strtoull(argv[2], nullptr, 10));
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    bool wanted = false;
    for (uint32_t id : selection.ids) wanted = wanted || id == parsed->ids[i];
    if (!wanted) continue;
    const meshwave::Status s = (*decoder)->AddPacket(parsed->ids[i], parsed->payloads[i]);
    if (!s.ok()) {
      std::fprintf(stderr, "%s\n", s.ToString().c_str());
      return 1;
    }
  }
  const meshwave::TriMesh mesh = (*decoder)->Mesh();
  std::printf("%zu packets, %zu vertices, %zu faces, estimated PSNR %.2f dB\n",
              (*decoder)->packets_decoded(), mesh.positions.size(), mesh.faces.size(),
              (*decoder)->EstimatedPsnr());
  std::ofstream out(argv[3], std::ios::binary);
  out << meshwave::SerializePly(mesh);
  return out ? 0 : 1;
}
