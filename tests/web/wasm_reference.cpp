// wasm_reference CONTAINER OUT_DIR: what the native decoder makes of a
// container at several budgets in the three orders, written for the
// WebAssembly decoder test (wasm_decoder_test.mjs) to compare with:
//   header.bin        the stream header (bytes without `present`)
//   CASE.packets      the selected packets: u32 id, u32 length, payload (LE)
//   CASE.pos64        positions at the finest level, float64 x,y,z (LE)
//   CASE.l1.pos64     positions at level 1
//   CASE.faces        faces at the finest level, u32 (LE)
//   manifest.json     {container: CONTAINER, cases: [...]}, per case: order,
//                     budget, and the decoder's level, levels, packets,
//                     payload bytes, estimated PSNR
// The selection is `meshwave decode --budget B --order O`'s (SelectPackets
// on PacketOrder). Links the decoder library alone.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"

namespace {

using namespace meshwave;

void PutU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(v >> (8 * i)));
}

template <class T>
std::string Raw(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

bool Write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

std::string Number(double v) {
  if (std::isinf(v)) return v > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string Flatten(const std::vector<Vec3>& p) {
  std::vector<double> out;
  for (const Vec3& v : p) out.insert(out.end(), {v.x(), v.y(), v.z()});
  return Raw(out);
}

int Run(const std::string& in, const std::string& dir) {
  std::ifstream file(in, std::ios::binary);
  std::stringstream ss;
  ss << file.rdbuf();
  const std::string bytes = ss.str();
  auto parsed = ParseContainer(bytes);
  if (!parsed.ok()) {
    std::fprintf(stderr, "%s: %s\n", in.c_str(), parsed.status().ToString().c_str());
    return 1;
  }
  StreamHeader header = parsed->header;
  header.present.clear();
  std::vector<std::string_view> payload(header.packets.length.size());
  for (size_t i = 0; i < parsed->ids.size(); ++i) payload[parsed->ids[i]] = parsed->payloads[i];
  if (!Write(dir + "/header.bin", header.bytes_without_present)) return 1;
  const uint64_t head = ContainerSize(header, {});
  const uint64_t full = bytes.size();
  std::string manifest = "{\"container\": \"" + in + "\", \"cases\": [\n";
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    const std::vector<uint32_t> order = PacketOrder(header, p);
    int k = 0;
    for (uint64_t budget : {head, head + (full - head) / 20, head + (full - head) / 5,
                            head + (full - head) / 2, full}) {
      const Selection s = SelectPackets(header, order, budget);
      auto decoder = ProgressiveDecoder::Create(header);
      if (!decoder.ok()) {
        std::fprintf(stderr, "%s\n", decoder.status().ToString().c_str());
        return 1;
      }
      std::string packets;
      for (uint32_t id : s.ids) {
        const Status st = (*decoder)->AddPacket(id, payload[id]);
        if (!st.ok()) {
          std::fprintf(stderr, "%s\n", st.ToString().c_str());
          return 1;
        }
        PutU32(packets, id);
        PutU32(packets, static_cast<uint32_t>(payload[id].size()));
        packets.append(payload[id]);
      }
      const std::string name = std::string(ProgressionName(p)) + "_" + std::to_string(k++);
      const TriMesh mesh = (*decoder)->Mesh();
      std::vector<uint32_t> faces;
      for (const Face& f : mesh.faces) faces.insert(faces.end(), f.begin(), f.end());
      if (!Write(dir + "/" + name + ".packets", packets) ||
          !Write(dir + "/" + name + ".pos64", Flatten(mesh.positions)) ||
          !Write(dir + "/" + name + ".l1.pos64", Flatten((*decoder)->Positions(1))) ||
          !Write(dir + "/" + name + ".faces", Raw(faces))) {
        std::fprintf(stderr, "cannot write into %s\n", dir.c_str());
        return 1;
      }
      if (manifest.back() == '}') manifest += ",\n";
      manifest += "{\"name\": \"" + name + "\", \"order\": \"" + ProgressionName(p) +
                  "\", \"budget\": " + std::to_string(budget) +
                  ", \"packets\": " + std::to_string((*decoder)->packets_decoded()) +
                  ", \"payloadBytes\": " + std::to_string((*decoder)->payload_bytes_decoded()) +
                  ", \"level\": " + std::to_string((*decoder)->CompleteLevels()) +
                  ", \"detailLevels\": " + std::to_string((*decoder)->DetailLevels()) +
                  ", \"levels\": " + std::to_string(header.transform.levels) +
                  ", \"packetCount\": " + std::to_string((*decoder)->packet_count()) +
                  ", \"psnr\": " + Number((*decoder)->EstimatedPsnr()) + "}";
    }
  }
  manifest += "\n]}\n";
  return Write(dir + "/manifest.json", manifest) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::printf("usage: wasm_reference CONTAINER.mwv OUT_DIR\n"
                "Writes the native decoder's output at several budgets in the three orders\n"
                "(tests/web/wasm_decoder_test.mjs compares the WebAssembly decoder with it).\n");
    return 0;
  }
  if (argc != 3) {
    std::fprintf(stderr, "usage: wasm_reference CONTAINER.mwv OUT_DIR (--help)\n");
    return 2;
  }
  return Run(argv[1], argv[2]);
}
