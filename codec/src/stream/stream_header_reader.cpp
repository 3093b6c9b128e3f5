// ReadStreamHeader: the one protobuf message the decoder needs, field by
// field as in proto/stream.proto, read with the general wire reader
// (core/protobuf_wire_reader.h), whose rules are protobuf 3.21's parser's,
// so both accept and refuse the same bytes; tests/fuzz/stream_header_fuzz.cpp
// compares them.
#include "meshwave/stream_header.h"

#include "core/protobuf_wire_reader.h"
#include "stream/stream_format.h"
#include "stream/utf8.h"

namespace meshwave {
namespace {

// Protobuf's default recursion limit: embedded messages and groups nest at
// most this deep below the header.
constexpr int kMaxDepth = 100;

wire::Field ReadSawt(uint32_t number, uint32_t type, wire::WireReader& r,
                     StreamHeader::SawtChoices& s) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, s.alpha);
    case 2: return wire::ReadVarint32(type, r, s.region_count);
    case 3: return wire::ReadBytes(type, r, s.coded);
    case 4: return wire::ReadFixed32(type, r, s.crc32c);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadTransform(uint32_t number, uint32_t type, wire::WireReader& r, int depth,
                          StreamHeader::Transform& t) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, t.predictor);
    case 2: return wire::ReadVarint32(type, r, t.update);
    case 3: return wire::ReadBool(type, r, t.local_frames);
    case 4: return wire::ReadVarint32(type, r, t.levels);
    case 5:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      // A repeated embedded message merges into the one already read.
      if (!t.sawt) t.sawt = StreamHeader::SawtChoices();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadSawt(n, w, f, *t.sawt);
      });
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadBase(uint32_t number, uint32_t type, wire::WireReader& r,
                     StreamHeader::BaseMesh& b) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, b.vertex_count);
    case 2: return wire::ReadVarint32(type, r, b.face_count);
    case 3: return wire::ReadRepeatedFixed<double>(type, r, b.origin);
    case 4: return wire::ReadDouble(type, r, b.step);
    case 6: return wire::ReadBytes(type, r, b.coded);
    case 7: return wire::ReadVarint32(type, r, b.refinement_planes);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadQuantizer(uint32_t number, uint32_t type, wire::WireReader& r,
                          StreamHeader::Quantizer& q) {
  switch (number) {
    case 1: return wire::ReadDouble(type, r, q.step);
    case 2: return wire::ReadVarint32(type, r, q.deadzone);
    case 3: return wire::ReadVarint32(type, r, q.top_bitplane);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadIndex(uint32_t number, uint32_t type, wire::WireReader& r,
                      StreamHeader::PacketIndex& p) {
  switch (number) {
    case 3: return wire::ReadRepeatedU32(type, r, p.length);
    case 6: return wire::ReadBytes(type, r, p.check);
    case 7: return wire::ReadRepeatedFixed<float>(type, r, p.chain_distortion);
    case 8: return wire::ReadBytes(type, r, p.distortion_step);
    case 9: return wire::ReadVarint32(type, r, p.precinct_coefficients);
    case 10: return wire::ReadRepeatedU32(type, r, p.split_planes);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadChannel(uint32_t number, uint32_t type, wire::WireReader& r, int depth,
                        StreamHeader::Channel& c) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, c.kind);
    case 2: return wire::ReadDouble(type, r, c.base_step);
    case 3: return wire::ReadBytes(type, r, c.base);
    case 4:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      c.quantizers.emplace_back();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadQuantizer(n, w, f, c.quantizers.back());
      });
    case 5: return wire::ReadFloat(type, r, c.rd_weight);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadTextureLevel(uint32_t number, uint32_t type, wire::WireReader& r,
                             StreamHeader::Texture::Level& l) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, l.packet);
    case 2: return wire::ReadVarint32(type, r, l.width);
    case 3: return wire::ReadVarint32(type, r, l.height);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadTextureMap(uint32_t number, uint32_t type, wire::WireReader& r, int depth,
                           StreamHeader::Texture::Map& m) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, m.role);
    case 2: {
      const wire::Field f = wire::ReadBytes(type, r, m.mime_type);
      if (f == wire::Field::kRead && !IsValidUtf8(m.mime_type)) return wire::Field::kError;
      return f;
    }
    case 3:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      m.levels.emplace_back();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadTextureLevel(n, w, f, m.levels.back());
      });
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadTexture(uint32_t number, uint32_t type, wire::WireReader& r, int depth,
                        StreamHeader::Texture& t) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, t.cell);
    case 2: return wire::ReadVarint32(type, r, t.gutter);
    case 3: return wire::ReadVarint32(type, r, t.columns);
    case 4: return wire::ReadRepeatedU32(type, r, t.face_triangles);
    case 5: return wire::ReadFloat(type, r, t.metallic_factor);
    case 6: return wire::ReadFloat(type, r, t.roughness_factor);
    case 7: return wire::ReadRepeatedFixed<float>(type, r, t.emissive_factor);
    case 8: return wire::ReadFloat(type, r, t.normal_scale);
    case 9: return wire::ReadFloat(type, r, t.occlusion_strength);
    case 10: return wire::ReadBool(type, r, t.alpha_blend);
    case 11: return wire::ReadBool(type, r, t.double_sided);
    case 12:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      t.maps.emplace_back();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int d) {
        return ReadTextureMap(n, w, f, d, t.maps.back());
      });
    case 13: return wire::ReadFloat(type, r, t.rd_weight);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadOriginal(uint32_t number, uint32_t type, wire::WireReader& r,
                         StreamHeader::Original& o) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, o.vertex_count);
    case 2: return wire::ReadU64(type, r, o.face_count);
    case 3: return wire::ReadRepeatedFixed<double>(type, r, o.origin);
    case 4: return wire::ReadDouble(type, r, o.step);
    case 5: return wire::ReadVarint32(type, r, o.extent);
    case 6: return wire::ReadVarint32(type, r, o.refinement_planes);
    default: return wire::Field::kUnknown;
  }
}

wire::Field ReadHeaderField(uint32_t number, uint32_t type, wire::WireReader& r, int depth,
                            StreamHeader& h) {
  switch (number) {
    case 1: return wire::ReadVarint32(type, r, h.format_version);
    case 2: {
      const wire::Field f = wire::ReadBytes(type, r, h.name);
      // proto3 strings must be UTF-8: protobuf refuses the message otherwise.
      if (f == wire::Field::kRead && !IsValidUtf8(h.name)) return wire::Field::kError;
      return f;
    }
    case 3: return wire::ReadU64(type, r, h.vertices);
    case 4: return wire::ReadU64(type, r, h.faces);
    case 5: return wire::ReadRepeatedFixed<double>(type, r, h.bbox_min);
    case 6: return wire::ReadRepeatedFixed<double>(type, r, h.bbox_max);
    case 7:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int d) {
        return ReadTransform(n, w, f, d, h.transform);
      });
    case 8: return wire::ReadVarint32(type, r, h.coder);
    case 9: return wire::ReadVarint32(type, r, h.octree_leaf_size);
    case 10:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadBase(n, w, f, h.base);
      });
    case 11:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      h.quantizers.emplace_back();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadQuantizer(n, w, f, h.quantizers.back());
      });
    case 12:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadIndex(n, w, f, h.packets);
      });
    case 13: return wire::ReadDouble(type, r, h.base_distortion);
    case kHeaderPresentField: return wire::ReadRepeatedU32(type, r, h.present);
    case 15:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      h.channels.emplace_back();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int d) {
        return ReadChannel(n, w, f, d, h.channels.back());
      });
    case 16:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      // A repeated embedded message merges into the one already read.
      if (!h.texture) h.texture = StreamHeader::Texture();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int d) {
        return ReadTexture(n, w, f, d, *h.texture);
      });
    case 17:
      if (type != kLengthDelimited) return wire::Field::kUnknown;
      if (!h.original) h.original = StreamHeader::Original();
      return wire::ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, wire::WireReader& f, int) {
        return ReadOriginal(n, w, f, *h.original);
      });
    default: return wire::Field::kUnknown;
  }
}

}  // namespace

Result<StreamHeader> ReadStreamHeader(std::string_view bytes) {
  StreamHeader h;
  const bool ok = wire::ReadMessage(
      bytes, kMaxDepth,
      [&](uint32_t number, uint32_t type, wire::WireReader& r, int depth) {
        return ReadHeaderField(number, type, r, depth, h);
      },
      [&](uint32_t tag, const char* begin, const char* end, bool known) {
        if (!(known && (tag >> 3) == kHeaderPresentField)) h.bytes_without_present.append(begin, end);
      });
  if (!ok) return ParseError("the stream header does not parse (malformed protobuf bytes)");
  return h;
}

}  // namespace meshwave
