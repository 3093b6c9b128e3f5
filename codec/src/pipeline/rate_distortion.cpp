// MeasureRdCurve: encode, then decode packet by packet in quality order and
// measure every prefix.
#include "meshwave/rate_distortion.h"

#include <cmath>
#include <limits>
#include <span>

#include "meshwave/container.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/metrics.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "pgc/pgc_stream.h"
#include "stream/packet_index.h"

namespace meshwave {
namespace {

// Adds the point of a prefix: `ids` decoded, `positions` reconstructed.
// `complete`: the bitplane this prefix completes, or -1.
Status AddPoint(const SemiRegularMesh& mesh, double diagonal,
                const StreamHeader& header, std::span<const uint32_t> ids,
                int complete, const std::vector<Vec3>& positions, RdCurve& curve) {
  MW_ASSIGN_OR_RETURN(VertexErrorStats error,
                      VertexError(mesh.positions, positions, diagonal));
  RdPoint p;
  p.packets = ids.size();
  p.bytes_total = ContainerSize(header, ids);
  for (uint32_t id : ids) p.payload_bytes += header.packets.length[id];
  const auto v = static_cast<double>(curve.vertices);
  p.bpv_total = 8.0 * static_cast<double>(p.bytes_total) / v;
  p.bpv_excl_base = 8.0 * static_cast<double>(p.payload_bytes) / v;
  p.psnr_db = error.psnr_db;
  p.bitplane_complete = complete;
  curve.points.push_back(p);
  return Status::Ok();
}

// Each stream carries the mesh in its own vertex order (the encoders
// renumber the base); decoded positions are compared with that.
Status MeasureEmbedded(const SemiRegularMesh& input, double diagonal,
                       CoderKind kind, const EncodeOptions& options,
                       RdCurve& curve) {
  EncodeOptions o = options;
  o.coder = kind;
  MW_ASSIGN_OR_RETURN(EncodedStream stream, EncodeMesh(input, o));
  const SemiRegularMesh& mesh = stream.mesh;
  MW_ASSIGN_OR_RETURN(std::unique_ptr<ProgressiveDecoder> decoder,
                      ProgressiveDecoder::Create(stream.header));
  curve.vertices = stream.header.vertices;
  const std::vector<uint32_t> order = PacketOrder(stream.header, Progression::kQuality);
  MW_RETURN_IF_ERROR(
      AddPoint(mesh, diagonal, stream.header, {}, -1, decoder->Positions(), curve));
  const PacketLayout layout(stream.header);
  auto bitplane = [&](size_t i) { return layout.Bitplane(order[i]); };
  // The bitplane of the first detail packet after position i (-1: none);
  // base refinement planes sit between the details' bitplanes.
  auto next_detail_bitplane = [&](size_t i) {
    for (size_t k = i + 1; k < order.size(); ++k) {
      if (!layout.IsBase(order[k])) return bitplane(k);
    }
    return -1;
  };
  for (size_t i = 0; i < order.size(); ++i) {
    MW_RETURN_IF_ERROR(decoder->AddPacket(order[i], stream.packets[order[i]]));
    // The quality order is bitplane-major: the details' bitplane is
    // complete where the next detail packet belongs to a lower one.
    const bool complete =
        !layout.IsBase(order[i]) && next_detail_bitplane(i) != bitplane(i);
    MW_RETURN_IF_ERROR(AddPoint(mesh, diagonal, stream.header,
                                std::span(order).first(i + 1),
                                complete ? bitplane(i) : -1, decoder->Positions(),
                                curve));
  }
  return Status::Ok();
}

Status MeasurePgc(const SemiRegularMesh& input, double diagonal,
                  const EncodeOptions& options, RdCurve& curve) {
  MW_ASSIGN_OR_RETURN(PgcStream stream, EncodePgc(input, options));
  const SemiRegularMesh& mesh = stream.mesh;
  MW_ASSIGN_OR_RETURN(std::unique_ptr<PgcDecoder> decoder,
                      PgcDecoder::Create(stream.header));
  curve.vertices = stream.header.vertices;
  std::vector<uint32_t> ids(stream.packets.size());
  for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  MW_RETURN_IF_ERROR(
      AddPoint(mesh, diagonal, stream.header, {}, -1, decoder->Positions(), curve));
  for (size_t i = 0; i < ids.size(); ++i) {
    MW_RETURN_IF_ERROR(decoder->AddPacket(stream.packets[i]));
    MW_RETURN_IF_ERROR(AddPoint(
        mesh, diagonal, stream.header, std::span(ids).first(i + 1),
        decoder->top_bitplane() - static_cast<int>(i),
        decoder->Positions(), curve));
  }
  return Status::Ok();
}

}  // namespace

Result<RdCoder> ParseRdCoder(const std::string& name) {
  if (name == "3xc" || name == "3xC") return RdCoder::k3xC;
  if (name == "sim") return RdCoder::kSim;
  if (name == "pgc") return RdCoder::kPgc;
  return InvalidArgument("unknown coder \"" + name + "\" (expected 3xc, sim or pgc)");
}

const char* RdCoderName(RdCoder coder) {
  switch (coder) {
    case RdCoder::k3xC: return "3xc";
    case RdCoder::kSim: return "sim";
    case RdCoder::kPgc: return "pgc";
  }
  return "?";
}

Result<RdCurve> MeasureRdCurve(const SemiRegularMesh& mesh, RdCoder coder,
                               const EncodeOptions& options) {
  RdCurve curve;
  curve.coder = coder;
  // The encoders use the same diagonal for their steps and refuse a zero one.
  const double diagonal = BoundingBox(mesh.positions).Diagonal();
  switch (coder) {
    case RdCoder::k3xC:
      MW_RETURN_IF_ERROR(MeasureEmbedded(mesh, diagonal, CoderKind::k3xC, options, curve));
      break;
    case RdCoder::kSim:
      MW_RETURN_IF_ERROR(MeasureEmbedded(mesh, diagonal, CoderKind::kSim, options, curve));
      break;
    case RdCoder::kPgc:
      MW_RETURN_IF_ERROR(MeasurePgc(mesh, diagonal, options, curve));
      break;
  }
  return curve;
}

const RdPoint* PointAtBitplane(const RdCurve& curve, int b) {
  for (const RdPoint& p : curve.points) {
    if (p.bitplane_complete == b) return &p;
  }
  return nullptr;
}

double PsnrAtBpv(const RdCurve& curve, double bpv_excl_base) {
  const auto& pts = curve.points;
  // From the end: at a rate shared by several points (empty packets, or the
  // rate of a point exactly) the one with the most packets counts.
  for (size_t i = pts.size(); i-- > 1;) {
    const RdPoint& a = pts[i - 1];
    const RdPoint& b = pts[i];
    if (bpv_excl_base < a.bpv_excl_base || bpv_excl_base > b.bpv_excl_base) continue;
    if (bpv_excl_base == b.bpv_excl_base) return b.psnr_db;
    const double t = (bpv_excl_base - a.bpv_excl_base) / (b.bpv_excl_base - a.bpv_excl_base);
    return a.psnr_db + t * (b.psnr_db - a.psnr_db);
  }
  if (!pts.empty() && bpv_excl_base == pts[0].bpv_excl_base) return pts[0].psnr_db;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace meshwave
