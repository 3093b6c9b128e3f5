// wasm_reference CONTAINER OUT_DIR: what the native decoder makes of a
// container at several budgets in the three orders, written for the
// WebAssembly decoder test (wasm_decoder_test.mjs) to compare with:
//   header.bin        the stream header (bytes without `present`)
//   CASE.packets      the selected packets: u32 id, u32 length, payload (LE)
//   CASE.pos64        positions at the finest level, float64 x,y,z (LE)
//   CASE.l1.pos64     positions at level 1
//   CASE.faces        faces at the finest level, u32 (LE)
//   CASE.col64        a stream with a colour channel only: colours at the
//                     finest level, float64 r,g,b (LE)
//   CASE.uv32         a stream with a texture only: texture coordinates per
//                     face corner at the finest level, float32 u,v (LE)
//   CASE.map0         ... and the base colour map's finest level held (its
//                     image bytes; absent when none is held)
//   PARTS.units       a stream with split packets (docs/FORMAT.md 2.2) only:
//                     units fed one by one, u32 id, u32 part + 1 (0: the
//                     whole packet), u32 length, payload (LE); the parts
//                     are the library's cut (PacketParts)
//   manifest.json     {container: CONTAINER, cases: [...], partCases: [...],
//                     split: [[id, parts], ...]}, per case: order, budget,
//                     and the decoder's level, levels, packets, payload
//                     bytes, estimated PSNR
// The selection is `meshwave decode --budget B --order O`'s (SelectPackets
// on PacketOrder). The part cases follow the region order (RegionOrder) of
// a sphere around the finest subband's first precinct: parts_0 its units
// up to 40 % of the payload bytes; parts_1 those, then every packet not
// held whole in the quality order (which decodes only the parts missing);
// parts_2 the whole region order. Links the decoder library alone.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/region_order.h"

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

// The base colour map's finest level held, when there is one.
bool WriteBaseColorLevel(const std::string& path, const ProgressiveDecoder& decoder) {
  const TextureInfo& info = decoder.texture();
  for (size_t m = 0; m < info.maps.size(); ++m) {
    if (info.maps[m].role != TextureRole::kBaseColor) continue;
    const std::optional<TextureImage> image = decoder.BestTextureLevel(m);
    return !image || Write(path, std::string(image->bytes));
  }
  return true;
}

// The decoder's mesh and counts for case `name`: its .pos64, .l1.pos64 and
// .faces files, and the fields of its manifest entry after "name".
bool WriteCase(const std::string& dir, const std::string& name, const ProgressiveDecoder& decoder,
               std::string& entry) {
  const TriMesh mesh = decoder.Mesh();
  std::vector<uint32_t> faces;
  for (const Face& f : mesh.faces) faces.insert(faces.end(), f.begin(), f.end());
  if (!Write(dir + "/" + name + ".pos64", Flatten(mesh.positions)) ||
      !Write(dir + "/" + name + ".l1.pos64", Flatten(decoder.Positions(1))) ||
      !Write(dir + "/" + name + ".faces", Raw(faces)) ||
      (decoder.HasColors() && !Write(dir + "/" + name + ".col64", Flatten(decoder.Colors()))) ||
      (decoder.HasTexture() &&
       !Write(dir + "/" + name + ".uv32", Raw(decoder.TextureCoordinates()))) ||
      !WriteBaseColorLevel(dir + "/" + name + ".map0", decoder)) {
    std::fprintf(stderr, "cannot write into %s\n", dir.c_str());
    return false;
  }
  entry = ", \"packets\": " + std::to_string(decoder.packets_decoded()) +
          ", \"payloadBytes\": " + std::to_string(decoder.payload_bytes_decoded()) +
          ", \"level\": " + std::to_string(decoder.CompleteLevels()) +
          ", \"detailLevels\": " + std::to_string(decoder.DetailLevels()) +
          ", \"levels\": " + std::to_string(decoder.header().transform.levels) +
          ", \"packetCount\": " + std::to_string(decoder.packet_count()) +
          ", \"psnr\": " + Number(decoder.EstimatedPsnr()) + "}";
  return true;
}

void PutUnit(std::string& out, uint32_t id, uint32_t tag, std::string_view payload) {
  PutU32(out, id);
  PutU32(out, tag);
  PutU32(out, static_cast<uint32_t>(payload.size()));
  out.append(payload);
}

// The part cases (see the top of the file) of a stream with split packets:
// their manifest entries, and the split packets' part counts in `split`.
bool WritePartCases(const std::string& dir, const StreamHeader& header,
                    const std::vector<std::string_view>& payload, std::string& entries,
                    std::string& split) {
  auto fail = [](const Status& s) {
    std::fprintf(stderr, "%s\n", s.ToString().c_str());
    return false;
  };
  auto precincts = StreamPrecincts::Create(header);
  if (!precincts.ok()) return fail(precincts.status());
  const HeldUnits none(header, precincts->parents());
  std::vector<std::vector<uint32_t>> part_lengths;
  for (uint32_t id = 0; id < payload.size(); ++id) {
    auto lengths = PartLengths(none, id, payload[id]);
    if (!lengths.ok()) return fail(lengths.status());
    part_lengths.push_back(std::move(*lengths));
    if (none.PartCount(id) == 0) continue;
    // Piece by piece: "[" + std::to_string(...) trips GCC 12's -Wrestrict
    // (a false positive in libstdc++'s operator+).
    if (!split.empty()) split += ", ";
    split += '[';
    split += std::to_string(id);
    split += ", ";
    split += std::to_string(none.PartCount(id));
    split += ']';
  }
  if (split.empty()) return true;
  // The finest subband's first precinct, as a sphere: what a client looking
  // at that patch gets first.
  const int j = precincts->levels() - 1;
  const Region region{SphereRegion{precincts->centre(j, 0), precincts->radius(j, 0)}, {}};
  const std::vector<StreamUnit> order =
      RegionOrder(header, *precincts, part_lengths, region, none);
  uint64_t total = 0;
  for (std::string_view p : payload) total += p.size();

  // parts_k: a fresh decoder fed order[0 .. prefix), then, for parts_1,
  // every packet it lacks whole in the quality order, for parts_2 the rest
  // of the region order.
  const std::vector<uint32_t> quality = PacketOrder(header, Progression::kQuality);
  for (int k = 0; k < 3; ++k) {
    auto decoder = ProgressiveDecoder::Create(header);
    if (!decoder.ok()) return fail(decoder.status());
    ProgressiveDecoder& d = **decoder;
    std::string units;
    uint64_t bytes = 0;
    for (const StreamUnit& u : order) {
      if (k < 2 && 5 * bytes >= 2 * total) break;  // 40 % of the payload bytes
      std::string_view data = payload[u.id];
      if (!u.whole()) {
        auto parts = PacketParts(none, u.id, data);
        if (!parts.ok()) return fail(parts.status());
        data = (*parts)[u.part];
      }
      const Status s = u.whole() ? d.AddPacket(u.id, data) : d.AddPacketPart(u.id, u.part, data);
      if (!s.ok()) return fail(s);
      PutUnit(units, u.id, u.whole() ? 0 : u.part + 1, data);
      bytes += data.size();
    }
    for (uint32_t id : quality) {
      if (k != 1 || d.HasPacket(id)) continue;
      if (Status s = d.AddPacket(id, payload[id]); !s.ok()) return fail(s);
      PutUnit(units, id, 0, payload[id]);
    }
    const std::string name = "parts_" + std::to_string(k);
    std::string entry;
    if (!Write(dir + "/" + name + ".units", units) || !WriteCase(dir, name, d, entry)) return false;
    if (!entries.empty()) entries += ",\n";
    entries += "{\"name\": \"" + name + "\"" + entry;
  }
  return true;
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
      std::string entry;
      if (!Write(dir + "/" + name + ".packets", packets) ||
          !WriteCase(dir, name, **decoder, entry)) {
        return 1;
      }
      if (manifest.back() == '}') manifest += ",\n";
      manifest += "{\"name\": \"" + name + "\", \"order\": \"" + ProgressionName(p) +
                  "\", \"budget\": " + std::to_string(budget) + entry;
    }
  }
  std::string part_cases, split;
  if (!WritePartCases(dir, header, payload, part_cases, split)) return 1;
  manifest += "\n], \"partCases\": [\n" + part_cases + "\n], \"split\": [" + split + "]}\n";
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
