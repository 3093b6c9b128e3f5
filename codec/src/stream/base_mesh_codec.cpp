#include "stream/base_mesh_codec.h"

#include <cmath>
#include <string>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"

namespace meshwave {
namespace {

constexpr uint32_t kMaxCoordinateBits = 32;

int BitsFor(uint64_t max_value) {
  int bits = 1;
  while (bits < 64 && (max_value >> bits) != 0) ++bits;
  return bits;
}

}  // namespace

Result<proto::BaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces,
                                       double step) {
  if (positions.empty() || faces.empty()) {
    return InvalidArgument("empty base mesh");
  }
  if (!(step > 0) || !std::isfinite(step)) {
    return InvalidArgument("base quantisation step must be positive");
  }
  Vec3 origin = positions[0];
  for (const Vec3& p : positions) origin = origin.cwiseMin(p);
  std::vector<uint64_t> q(3 * positions.size());
  uint64_t max_q = 0;
  for (size_t v = 0; v < positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const double x = std::round((positions[v][a] - origin[a]) / step);
      if (!(x >= 0) || x >= 4294967295.0) {
        return InvalidArgument(
            "base mesh does not fit a 32-bit grid at this precision");
      }
      q[3 * v + a] = static_cast<uint64_t>(x);
      max_q = std::max(max_q, q[3 * v + a]);
    }
  }
  const int coord_bits = BitsFor(max_q);
  const int index_bits = BitsFor(positions.size() - 1);
  ArithmeticEncoder enc;
  for (uint64_t x : q) enc.EncodeBits(static_cast<uint32_t>(x), coord_bits);
  for (const Face& f : faces) {
    for (uint32_t v : f) enc.EncodeBits(v, index_bits);
  }
  proto::BaseMesh out;
  out.set_vertex_count(static_cast<uint32_t>(positions.size()));
  out.set_face_count(static_cast<uint32_t>(faces.size()));
  for (int a = 0; a < 3; ++a) out.add_origin(origin[a]);
  out.set_step(step);
  out.set_coordinate_bits(static_cast<uint32_t>(coord_bits));
  out.set_coded(enc.Finish());
  return out;
}

Result<DecodedBase> DecodeBaseMesh(const proto::BaseMesh& base,
                                   uint32_t max_vertices) {
  const uint64_t v = base.vertex_count(), f = base.face_count();
  if (v == 0 || f == 0) return ParseError("base mesh: no vertices or faces");
  if (v > max_vertices) {
    return ParseError("base mesh: " + std::to_string(v) +
                      " vertices exceed the limit of " +
                      std::to_string(max_vertices));
  }
  const uint32_t coord_bits = base.coordinate_bits();
  if (coord_bits == 0 || coord_bits > kMaxCoordinateBits) {
    return ParseError("base mesh: bad coordinate width " +
                      std::to_string(coord_bits));
  }
  if (base.origin_size() != 3 || !(base.step() > 0) ||
      !std::isfinite(base.step())) {
    return ParseError("base mesh: bad origin or step");
  }
  for (double o : base.origin()) {
    if (!std::isfinite(o)) return ParseError("base mesh: origin is not finite");
  }
  const int index_bits = BitsFor(v - 1);
  // Fixed-width bits: the coded size bounds both counts before allocating.
  const double needed_bits =
      3.0 * static_cast<double>(v) * coord_bits + 3.0 * static_cast<double>(f) * index_bits;
  if (needed_bits > 8.0 * (static_cast<double>(base.coded().size()) + 8)) {
    return ParseError("base mesh: " + std::to_string(v) + " vertices and " +
                      std::to_string(f) + " faces need more than the " +
                      std::to_string(base.coded().size()) + " coded bytes");
  }
  ArithmeticDecoder dec(base.coded());
  DecodedBase out;
  out.grid.resize(v);
  out.positions.resize(v);
  for (uint64_t i = 0; i < v; ++i) {
    for (int a = 0; a < 3; ++a) {
      out.grid[i][a] = dec.DecodeBits(static_cast<int>(coord_bits));
      out.positions[i][a] =
          base.origin(a) + base.step() * static_cast<double>(out.grid[i][a]);
    }
  }
  out.faces.resize(f);
  for (uint64_t i = 0; i < f; ++i) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t index = dec.DecodeBits(index_bits);
      if (index >= v) {
        return ParseError("base mesh: face " + std::to_string(i) +
                          " uses vertex " + std::to_string(index) + " of " +
                          std::to_string(v));
      }
      out.faces[i][c] = index;
    }
  }
  if (dec.overrun()) return ParseError("base mesh: coded bytes truncated");
  return out;
}

}  // namespace meshwave
