// The stream header (proto/stream.proto's StreamHeader, docs/FORMAT.md 2)
// as plain C++ data, and its reader. The decoder library reads the header
// with this small reader of the protobuf wire format instead of protobuf's
// C++ runtime, so that it builds where that runtime does not (WebAssembly)
// and a decoder-only program does not link libprotobuf. The encoder still
// writes the header with protobuf (meshwave/stream_header_proto.h converts);
// tests/codec/stream/stream_header_test.cpp and tests/fuzz/
// stream_header_fuzz.cpp check that both read the same fields from the same
// bytes and refuse the same bytes.
#ifndef MESHWAVE_STREAM_HEADER_H_
#define MESHWAVE_STREAM_HEADER_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

// The stream format version this build writes (docs/FORMAT.md). 3:
// Transform.sawt; 4: compact packet index; 5: base refinement packets; 6:
// 3xC's significance contexts count significant neighbours; 7: precincts
// and split packets; 8: channels (per-vertex colours); 9: textures; 10:
// the original mesh as a final layer; 11: WebP texture levels.
inline constexpr uint32_t kStreamFormatVersion = 11;

// Enum fields keep whatever value the bytes hold, as protobuf's open proto3
// enums do: validation (ValidateStreamHeader), not reading, refuses values
// it does not know.
enum class StreamPredictor : int32_t { kLinear = 0, kButterfly = 1, kLoop = 2, kSawt = 3 };
enum class StreamUpdate : int32_t { kNone = 0, kConstant = 1, kValence = 2 };
enum class StreamCoder : int32_t { k3xC = 0, kSim = 1 };
enum class StreamChannelKind : int32_t { kNone = 0, kColor = 1 };

// Field by field as in proto/stream.proto (the comments there say what
// each field means).
struct StreamHeader {
  struct SawtChoices {
    uint32_t alpha = 0;
    uint32_t region_count = 0;
    std::string coded;
    uint32_t crc32c = 0;
  };
  struct Transform {
    StreamPredictor predictor = StreamPredictor::kLinear;
    StreamUpdate update = StreamUpdate::kNone;
    bool local_frames = false;
    uint32_t levels = 0;
    std::optional<SawtChoices> sawt;  // present or not, as on the wire
  };
  struct BaseMesh {
    uint32_t vertex_count = 0;
    uint32_t face_count = 0;
    std::vector<double> origin;
    double step = 0;  // of the finest grid
    std::string coded;
    uint32_t refinement_planes = 0;  // the coded grid is 2^this coarser
  };
  struct Quantizer {
    double step = 0;
    uint32_t deadzone = 0;
    int32_t top_bitplane = 0;
  };
  struct PacketIndex {
    std::vector<uint32_t> length;
    std::string check;
    std::vector<float> chain_distortion;
    std::string distortion_step;
    uint32_t precinct_coefficients = 0;
    std::vector<uint32_t> split_planes;
  };
  struct Channel {
    StreamChannelKind kind = StreamChannelKind::kNone;
    double base_step = 0;
    std::string base;
    std::vector<Quantizer> quantizers;  // subband-major, as the geometry's
    float rd_weight = 0;

    const Quantizer& quantizer(int j, int c) const {
      return quantizers[3 * static_cast<size_t>(j) + static_cast<size_t>(c)];
    }
  };

  // Version 9 (docs/FORMAT.md 2.4). Fields left out on the wire read as
  // protobuf's defaults (0), whatever the material's defaults are.
  struct Texture {
    struct Level {
      uint32_t packet = 0;
      uint32_t width = 0;
      uint32_t height = 0;
    };
    struct Map {
      int32_t role = 0;  // TextureRole's values; validation refuses others
      std::string mime_type;
      std::vector<Level> levels;  // coarsest first
    };
    uint32_t cell = 0;
    uint32_t gutter = 0;
    uint32_t columns = 0;
    std::vector<uint32_t> face_triangles;  // empty: base face f owns triangle f
    float metallic_factor = 0;
    float roughness_factor = 0;
    std::vector<float> emissive_factor;
    float normal_scale = 0;
    float occlusion_strength = 0;
    bool alpha_blend = false;
    bool double_sided = false;
    std::vector<Map> maps;
    float rd_weight = 0;
  };

  // Version 10 (docs/FORMAT.md 2.5).
  struct Original {
    uint32_t vertex_count = 0;
    uint64_t face_count = 0;
    std::vector<double> origin;
    double step = 0;
    uint32_t extent = 0;
    uint32_t refinement_planes = 0;
  };

  uint32_t format_version = 0;
  std::string name;
  uint64_t vertices = 0;
  uint64_t faces = 0;
  std::vector<double> bbox_min;
  std::vector<double> bbox_max;
  Transform transform;
  StreamCoder coder = StreamCoder::k3xC;
  uint32_t octree_leaf_size = 0;
  BaseMesh base;
  std::vector<Quantizer> quantizers;  // subband-major: (j, c) at 3 j + c
  PacketIndex packets;
  double base_distortion = 0;
  std::vector<uint32_t> present;
  std::vector<Channel> channels;
  std::optional<Texture> texture;  // present or not, as on the wire
  std::optional<Original> original;  // present or not, as on the wire

  // The header's bytes without its `present` records: what a container
  // holding other packets starts its header with (SerializeContainerHead
  // appends `present`), and what ContainerSize counts. Protobuf writes
  // `present` last, so for bytes protobuf wrote this is exactly protobuf's
  // serialization of the header with `present` cleared.
  std::string bytes_without_present;

  // The quantizer of subband j, component c (ValidateStreamHeader checks
  // that there are 3 per level).
  const Quantizer& quantizer(int j, int c) const {
    return quantizers[3 * static_cast<size_t>(j) + static_cast<size_t>(c)];
  }
};

// Reads a serialized StreamHeader. Safe on untrusted bytes, and it accepts
// and refuses what protobuf's parser (3.21) does: unknown fields and groups
// are skipped, repeated numbers packed or not, a scalar's last value wins,
// embedded messages merge; a truncated or malformed record, a wrong group
// end, nesting deeper than 100, or a name that is not UTF-8 is an error
// (kParseError). It reads the wire format only: whether the fields make a
// stream is ValidateStreamHeader's business.
Result<StreamHeader> ReadStreamHeader(std::string_view bytes);

// The length of the header's bounding-box diagonal (0 for a box of fewer
// than three coordinates): the peak of every PSNR of the stream.
double HeaderDiagonal(const StreamHeader& header);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_HEADER_H_
