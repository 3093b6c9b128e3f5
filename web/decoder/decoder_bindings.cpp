// The WebAssembly face of the decoder library (embind): one class over
// ProgressiveDecoder whose fallible calls return the error message ("" when
// they succeed) instead of throwing. C++ exceptions across embind cost code
// size and speed; decoder_api.js turns the messages into JS Errors and is
// the API the page uses (docs/API.md, "JavaScript decoder").
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/stream_header.h"

namespace meshwave::wasm {
namespace {

using emscripten::val;

// A copy of `values` as a new JS typed array (`type`: its constructor name),
// so that the array outlives the wasm memory it came from.
template <class T>
val TypedArrayCopy(const char* type, const std::vector<T>& values) {
  return val::global(type).new_(emscripten::typed_memory_view(values.size(), values.data()));
}

class RawDecoder {
 public:
  // Reads and checks the header; "" or the reason it was refused.
  std::string Open(const std::string& header_bytes) {
    auto header = ReadStreamHeader(header_bytes);
    if (!header.ok()) return header.status().message();
    auto decoder = ProgressiveDecoder::Create(*header);
    if (!decoder.ok()) return decoder.status().message();
    decoder_ = std::move(*decoder);
    return "";
  }

  std::string AddPacket(uint32_t id, const std::string& payload) {
    return decoder_->AddPacket(id, payload).message();
  }

  // One precinct's part of a split packet (docs/FORMAT.md 2.2), as a
  // region stream sends it: "" or the reason it was refused.
  std::string AddPacketPart(uint32_t id, uint32_t part, const std::string& payload) {
    return decoder_->AddPacketPart(id, part, payload).message();
  }

  size_t PacketCount() const { return decoder_->packet_count(); }
  bool HasPacket(uint32_t id) const { return decoder_->HasPacket(id); }
  bool DependenciesMet(uint32_t id) const { return decoder_->DependenciesMet(id); }
  uint32_t PartCount(uint32_t id) const { return decoder_->PartCount(id); }
  bool HasPart(uint32_t id, uint32_t part) const { return decoder_->HasPart(id, part); }
  bool PartDependenciesMet(uint32_t id, uint32_t part) const {
    return decoder_->PartDependenciesMet(id, part);
  }
  int Level() const { return decoder_->CompleteLevels(); }
  int DetailLevels() const { return decoder_->DetailLevels(); }
  int Levels() const { return static_cast<int>(decoder_->header().transform.levels); }
  double EstimatedPsnr() const { return decoder_->EstimatedPsnr(); }
  size_t PacketsDecoded() const { return decoder_->packets_decoded(); }
  double PayloadBytesDecoded() const {
    return static_cast<double>(decoder_->payload_bytes_decoded());
  }

  // x, y, z interleaved, as float32 (what a GPU takes) or float64 (the
  // decoder's own values: the tests compare them bit for bit).
  val Positions(int max_level) const { return Interleaved<float>("Float32Array", max_level); }
  val Positions64(int max_level) const { return Interleaved<double>("Float64Array", max_level); }

  // Linear RGB per vertex of positions(max_level), interleaved; an empty
  // array when the stream has no colour channel.
  bool HasColors() const { return decoder_->HasColors(); }
  val Colors(int max_level) const {
    return InterleavedColors<float>("Float32Array", max_level);
  }
  val Colors64(int max_level) const {
    return InterleavedColors<double>("Float64Array", max_level);
  }

  // The texture (format 9): per face corner of faces(max_level), u and v
  // (the atlas gives them; they never travel); an empty array without one.
  bool HasTexture() const { return decoder_->HasTexture(); }
  val TextureCoordinates(int max_level) const {
    return TypedArrayCopy("Float32Array", decoder_->TextureCoordinates(ClampLevel(max_level)));
  }

  // The finest level held of the map with role `role` (TextureRole's
  // number): {bytes, mimeType, width, height, level, levels}, or null when
  // the stream has no such map or none of its levels arrived yet.
  val TextureImage(int role) const {
    const TextureInfo& info = decoder_->texture();
    for (size_t m = 0; m < info.maps.size(); ++m) {
      if (static_cast<int>(info.maps[m].role) != role) continue;
      const std::optional<meshwave::TextureImage> image = decoder_->BestTextureLevel(m);
      if (!image) return val::null();
      val out = val::object();
      out.set("bytes", TypedArrayCopy("Uint8Array", std::vector<uint8_t>(image->bytes.begin(),
                                                                          image->bytes.end())));
      out.set("mimeType", image->mime_type);
      out.set("width", image->width);
      out.set("height", image->height);
      out.set("level", image->level);
      out.set("levels", static_cast<uint32_t>(info.maps[m].levels.size()));
      return out;
    }
    return val::null();
  }

  val Faces(int max_level) const { return FlattenFaces(decoder_->Faces(max_level)); }

  // The original layer (format 10): the user's own mesh once held.
  bool OriginalReady() const { return decoder_->OriginalReady(); }
  val OriginalMesh() const {
    const TriMesh mesh = decoder_->OriginalMesh();
    val out = val::object();
    out.set("positions", Flatten<float>("Float32Array", mesh.positions));
    out.set("faces", FlattenFaces(mesh.faces));
    return out;
  }

 private:
  // Positions(level) as Mesh(level) takes it: -1 and levels beyond J mean J.
  int ClampLevel(int max_level) const {
    const int levels = Levels();
    return (max_level < 0 || max_level > levels) ? levels : max_level;
  }

  template <class T>
  val Interleaved(const char* type, int max_level) const {
    return Flatten<T>(type, decoder_->Positions(ClampLevel(max_level)));
  }

  template <class T>
  val InterleavedColors(const char* type, int max_level) const {
    return Flatten<T>(type, decoder_->Colors(ClampLevel(max_level)));
  }

  static val FlattenFaces(const std::vector<Face>& faces) {
    std::vector<uint32_t> out;
    out.reserve(3 * faces.size());
    for (const Face& f : faces) out.insert(out.end(), f.begin(), f.end());
    return TypedArrayCopy("Uint32Array", out);
  }

  template <class T>
  static val Flatten(const char* type, const std::vector<Vec3>& p) {
    std::vector<T> out(3 * p.size());
    for (size_t v = 0; v < p.size(); ++v) {
      for (int a = 0; a < 3; ++a) out[3 * v + static_cast<size_t>(a)] = static_cast<T>(p[v][a]);
    }
    return TypedArrayCopy(type, out);
  }

  std::unique_ptr<ProgressiveDecoder> decoder_;
};

// A .mwv container (maybe cut short): {error} or {header: the header's
// bytes without `present`, ids, offsets and lengths of the whole payloads
// in `bytes`, missingBytes}. decoder_api.js makes the payload views.
val ParseContainerRaw(const std::string& bytes) {
  val out = val::object();
  auto parsed = ParseContainer(bytes, /*allow_truncated=*/true);
  if (!parsed.ok()) {
    out.set("error", parsed.status().message());
    return out;
  }
  const std::string& header = parsed->header.bytes_without_present;
  out.set("header", TypedArrayCopy("Uint8Array", std::vector<uint8_t>(header.begin(), header.end())));
  std::vector<uint32_t> offsets, lengths;
  for (std::string_view p : parsed->payloads) {
    offsets.push_back(static_cast<uint32_t>(p.data() - bytes.data()));
    lengths.push_back(static_cast<uint32_t>(p.size()));
  }
  out.set("ids", TypedArrayCopy("Uint32Array", parsed->ids));
  out.set("offsets", TypedArrayCopy("Uint32Array", offsets));
  out.set("lengths", TypedArrayCopy("Uint32Array", lengths));
  out.set("missingBytes", static_cast<double>(parsed->missing_bytes));
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(meshwave_decoder) {
  emscripten::function("parseContainerRaw", &ParseContainerRaw);
  emscripten::class_<RawDecoder>("RawDecoder")
      .constructor<>()
      .function("open", &RawDecoder::Open)
      .function("addPacket", &RawDecoder::AddPacket)
      .function("packetCount", &RawDecoder::PacketCount)
      .function("hasPacket", &RawDecoder::HasPacket)
      .function("dependenciesMet", &RawDecoder::DependenciesMet)
      .function("addPacketPart", &RawDecoder::AddPacketPart)
      .function("partCount", &RawDecoder::PartCount)
      .function("hasPart", &RawDecoder::HasPart)
      .function("partDependenciesMet", &RawDecoder::PartDependenciesMet)
      .function("level", &RawDecoder::Level)
      .function("detailLevels", &RawDecoder::DetailLevels)
      .function("levels", &RawDecoder::Levels)
      .function("estimatedPsnr", &RawDecoder::EstimatedPsnr)
      .function("packetsDecoded", &RawDecoder::PacketsDecoded)
      .function("payloadBytesDecoded", &RawDecoder::PayloadBytesDecoded)
      .function("positions", &RawDecoder::Positions)
      .function("positions64", &RawDecoder::Positions64)
      .function("faces", &RawDecoder::Faces)
      .function("originalReady", &RawDecoder::OriginalReady)
      .function("originalMesh", &RawDecoder::OriginalMesh)
      .function("hasColors", &RawDecoder::HasColors)
      .function("colors", &RawDecoder::Colors)
      .function("colors64", &RawDecoder::Colors64)
      .function("hasTexture", &RawDecoder::HasTexture)
      .function("textureCoordinates", &RawDecoder::TextureCoordinates)
      .function("textureImage", &RawDecoder::TextureImage);
}

}  // namespace meshwave::wasm
