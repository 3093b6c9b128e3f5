#include "stream/stream_preparation.h"

#include <algorithm>
#include <cmath>

#include "stream/stream_format.h"

namespace meshwave {

namespace {

// The base mesh's quantisation step. The step step0 / sqrt(G_base) would
// give each base vertex the error of one finest coefficient; but there are
// V_J / V0 times more of those, so the base's share of the complete
// stream's error would be about V0 / V_J (under 2 %) while its positions
// cost up to half the header. Balancing the base's total error against a
// quarter of the finest subband's (step sqrt(V_J / V0) / 2 times coarser,
// never finer than the per-vertex rule) saves about 6 bits per base vertex
// and costs the complete stream about 1 dB (still far above 90 dB).
double BaseStep(const PreparedStream& p, const SemiRegularHierarchy& h) {
  const double ratio = static_cast<double>(h.vertex_count(h.levels())) /
                       static_cast<double>(h.vertex_count(0));
  return p.step0 / std::sqrt(p.gains.base) * std::max(1.0, 0.5 * std::sqrt(ratio));
}

}  // namespace

Result<PreparedStream> PrepareStream(const SemiRegularMesh& input,
                                     const EncodeOptions& options) {
  if (options.precision < 4 || options.precision > 30) {
    return InvalidArgument("precision must be in [4, 30]");
  }
  if (options.deadzone < 0 || options.deadzone > 3) {
    return InvalidArgument("deadzone code must be in [0, 3]");
  }
  PreparedStream out;
  // The base mesh travels in an order that codes cheaply; the hierarchy
  // (and so every coefficient's index) follows from that order.
  MW_ASSIGN_OR_RETURN(const BaseMeshOrder order, ChooseTransmissionOrder(
      input.hierarchy->vertex_count(0), input.hierarchy->faces(0)));
  MW_ASSIGN_OR_RETURN(out.mesh, RenumberBase(input, order.new_of_old, order.faces));
  const SemiRegularHierarchy& h = *out.mesh.hierarchy;
  const int levels = h.levels();
  const Aabb box = BoundingBox(out.mesh.positions);
  const double diag = box.Diagonal();
  if (!(diag > 0) || !std::isfinite(diag)) {
    return InvalidArgument("mesh has no extent (bounding-box diagonal is 0)");
  }
  out.step0 = std::ldexp(diag, -options.precision);
  out.gains = ComputeSubbandGains(options.transform, levels);
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(out.mesh.hierarchy, options.transform));
  out.pyramid = transform.Forward(out.mesh.positions);

  proto::StreamHeader& header = out.header;
  header.set_format_version(kFormatVersion);
  header.set_name(options.name);
  header.set_vertices(h.vertex_count(levels));
  header.set_faces(h.faces(levels).size());
  for (int a = 0; a < 3; ++a) {
    header.add_bbox_min(box.min[a]);
    header.add_bbox_max(box.max[a]);
  }
  ToProto(options.transform, levels, *header.mutable_transform());
  MW_ASSIGN_OR_RETURN(*header.mutable_base(),
                      EncodeBaseMesh(out.pyramid.base, h.faces(0), BaseStep(out, h)));
  MW_ASSIGN_OR_RETURN(out.base,
                      DecodeBaseMesh(header.base(), header.base().vertex_count()));
  for (size_t v = 0; v < out.base.positions.size(); ++v) {
    out.base_distortion +=
        out.gains.base * (out.pyramid.base[v] - out.base.positions[v]).squaredNorm();
  }
  // What a decoder holding no packet shows: the decoded base, no details.
  Pyramid coarse = out.pyramid;
  coarse.base = out.base.positions;
  for (auto& band : coarse.subbands) std::fill(band.begin(), band.end(), Vec3::Zero());
  const std::vector<Vec3> start = transform.Inverse(coarse);
  for (size_t v = 0; v < start.size(); ++v) {
    out.zero_packet_distortion += (start[v] - out.mesh.positions[v]).squaredNorm();
  }
  return out;
}

void CalibrateDistortionIndex(const PreparedStream& prepared,
                              proto::StreamHeader& header) {
  const double model = header.initial_distortion();
  const double truth = prepared.zero_packet_distortion;
  if (!(model > 0) || !(truth > 0) || !std::isfinite(model) || !std::isfinite(truth)) return;
  const double scale = truth / model;
  header.set_initial_distortion(truth);
  proto::PacketIndex& index = *header.mutable_packets();
  for (int i = 0; i < index.distortion_reduction_size(); ++i) {
    index.set_distortion_reduction(
        i, static_cast<float>(scale * index.distortion_reduction(i)));
  }
}

}  // namespace meshwave
