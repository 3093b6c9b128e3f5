#include "stream/stream_preparation.h"

#include <algorithm>
#include <cmath>

#include "mesh/vertex_normals.h"
#include "quant/deadzone_quantizer.h"
#include "stream/base_refinement.h"  // RefinedBasePosition, BaseRefinementBytes
#include "stream/sawt_field_encoder.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"
#include "wavelet/sawt_choice.h"
#include "wavelet/sawt_regions.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/subdivision.h"

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

// The grid a decoder will hold for these base positions.
Result<std::vector<IntVec3>> DecodedGrid(const std::vector<Vec3>& base, const PreparedStream& p,
                                         const SemiRegularHierarchy& h) {
  MW_ASSIGN_OR_RETURN(const EncodedBaseMesh coded,
                      EncodeBaseMesh(base, h.faces(0), BaseStep(p, h),
                                     p.header.base().refinement_planes()));
  MW_ASSIGN_OR_RETURN(DecodedBase decoded,
                      DecodeBaseMesh(coded.header, coded.header.vertex_count));
  return std::move(decoded.grid);
}

// base_error (PreparedStream): the error of the base with each number of
// low bits missing, as a decoder would place it, weighed as the details'
// is: along the base's vertex normals in full, the slide along the surface
// by `tangent_weight` (the grid's error is isotropic, so without this the
// order would value the base's low bits about three times too much).
std::vector<double> BaseErrors(const std::vector<Vec3>& exact, const std::vector<Face>& faces,
                               const EncodedBaseMesh& coded, const DecodedBase& decoded,
                               double gain, double tangent_weight) {
  const std::vector<Vec3> normals = VertexNormals(faces, exact, exact.size());
  const auto planes = static_cast<int>(coded.header.refinement_planes);
  std::vector<double> error(static_cast<size_t>(planes) + 1, 0.0);
  for (int m = 0; m <= planes; ++m) {
    const int64_t keep = ~((int64_t{1} << m) - 1);
    for (size_t v = 0; v < exact.size(); ++v) {
      const IntVec3& r = coded.residual[v];
      const IntVec3 known{r[0] & keep, r[1] & keep, r[2] & keep};
      const Vec3 e = RefinedBasePosition(coded.header, decoded.grid[v], known, m) - exact[v];
      const double along = e.dot(normals[v]);
      error[static_cast<size_t>(m)] +=
          gain * (along * along + tangent_weight * (e.squaredNorm() - along * along));
    }
  }
  return error;
}

// SAWT regions live on the decoded base grid, but with an update step the
// base positions depend on the filters chosen: iterate until the regions
// of the grid that the chosen transform produces are the ones it was
// chosen with (unlifted: the base is the mesh's own, one round).
Result<std::shared_ptr<const SawtPlan>> PlanSawt(const PreparedStream& p,
                                                 const EncodeOptions& options) {
  const SemiRegularHierarchy& h = *p.mesh.hierarchy;
  std::vector<Vec3> base(p.mesh.positions.begin(),
                         p.mesh.positions.begin() + h.vertex_count(0));
  const double lambda = options.sawt_lambda_scale * p.step0 * p.step0;
  const uint32_t alpha = std::max<uint32_t>(1, options.sawt_alpha);
  for (int round = 0; round < 8; ++round) {
    MW_ASSIGN_OR_RETURN(const std::vector<IntVec3> grid, DecodedGrid(base, p, h));
    SawtRegions regions = BuildSawtRegions(h, grid, alpha);
    MW_ASSIGN_OR_RETURN(std::shared_ptr<const SawtPlan> plan,
                        ChooseSawtFilters(h, regions, p.mesh.positions,
                                          options.transform.update, lambda));
    if (options.transform.update == UpdateWeights::kNone) return plan;
    TransformSettings settings = options.transform;
    settings.sawt = plan;
    MW_ASSIGN_OR_RETURN(WaveletTransform t, WaveletTransform::Create(p.mesh.hierarchy, settings));
    base = t.Forward(p.mesh.positions).base;
    MW_ASSIGN_OR_RETURN(const std::vector<IntVec3> moved, DecodedGrid(base, p, h));
    size_t next = 0;
    const SawtRegions seen = ReplaySawtRegions(h, moved, [&](int) {
      return next < plan->regions.split_flags.size() ? plan->regions.split_flags[next++] : 0;
    });
    if (next == plan->regions.split_flags.size() && seen.count == plan->regions.count &&
        seen.face_region == plan->regions.face_region) {
      return plan;
    }
  }
  return InvalidArgument(
      "SAWT with an update step: the base faces' regions kept moving with the filters "
      "chosen (8 rounds); encode with --update none");
}

}  // namespace

Result<uint32_t> ChooseBaseRefinementPlanes(const std::vector<Vec3>& positions,
                                            const std::vector<Face>& faces, double step) {
  MW_ASSIGN_OR_RETURN(const EncodedBaseMesh whole, EncodeBaseMesh(positions, faces, step, 0));
  const double limit = 1.02 * static_cast<double>(whole.header.coded.size());
  const double per_packet =
      static_cast<double>(BaseRefinementBytes(static_cast<uint32_t>(positions.size()))) + 5;
  uint32_t chosen = 0;
  for (uint32_t planes = 1; planes <= kMaxBaseRefinementPlanes; ++planes) {
    MW_ASSIGN_OR_RETURN(const EncodedBaseMesh coarse,
                        EncodeBaseMesh(positions, faces, step, planes));
    const double total = static_cast<double>(coarse.header.coded.size()) + planes * per_packet;
    if (total > limit) break;
    chosen = planes;
  }
  return chosen;
}

Result<PreparedStream> PrepareStream(const SemiRegularMesh& input,
                                     const EncodeOptions& options) {
  if (options.base_refinement_planes > static_cast<int>(kMaxBaseRefinementPlanes)) {
    return InvalidArgument("at most " + std::to_string(kMaxBaseRefinementPlanes) +
                           " base refinement planes");
  }
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
  MW_ASSIGN_OR_RETURN(out.mesh,
                      RenumberBase(input, order.new_of_old, order.faces, &out.input_vertex));
  const SemiRegularHierarchy& h = *out.mesh.hierarchy;
  const int levels = h.levels();
  const Aabb box = BoundingBox(out.mesh.positions);
  const double diag = box.Diagonal();
  if (!(diag > 0) || !std::isfinite(diag)) {
    return InvalidArgument("mesh has no extent (bounding-box diagonal is 0)");
  }
  out.step0 = std::ldexp(diag, -options.precision);
  out.tangent_step_scale =
      options.transform.frames == FrameMode::kLocal ? options.tangent_step_scale : 1.0;
  out.gains = ComputeSubbandGains(options.transform, levels);
  out.transform = options.transform;
  // Fixed before the SAWT plan, whose regions live on the coarse grid.
  uint32_t planes = 0;
  if (options.base_refinement_planes < 0) {
    const std::vector<Vec3> base(out.mesh.positions.begin(),
                                 out.mesh.positions.begin() + h.vertex_count(0));
    MW_ASSIGN_OR_RETURN(planes, ChooseBaseRefinementPlanes(base, h.faces(0), BaseStep(out, h)));
  } else {
    planes = static_cast<uint32_t>(options.base_refinement_planes);
  }
  out.header.mutable_base()->set_refinement_planes(planes);
  if (out.transform.predictor == Predictor::kSawt) {
    MW_ASSIGN_OR_RETURN(out.transform.sawt, PlanSawt(out, options));
  }
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(out.mesh.hierarchy, out.transform));
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
  ToProto(out.transform, levels, *header.mutable_transform());
  MW_ASSIGN_OR_RETURN(EncodedBaseMesh base,
                      EncodeBaseMesh(out.pyramid.base, h.faces(0), BaseStep(out, h), planes));
  ToProto(base.header, *header.mutable_base());
  MW_ASSIGN_OR_RETURN(out.base, DecodeBaseMesh(base.header, base.header.vertex_count));
  if (out.transform.sawt) {
    ToProto(EncodeSawtChoices(h, out.base.grid, *out.transform.sawt, options.sawt_alpha),
            *header.mutable_transform()->mutable_sawt());
  }
  const double tangent_weight = 1 / (out.tangent_step_scale * out.tangent_step_scale);
  out.base_error = BaseErrors(out.pyramid.base, h.faces(0), base, out.base, out.gains.base,
                              tangent_weight);
  out.base_distortion = out.base_error[0];
  out.base_residual = std::move(base.residual);
  // What a decoder holding no packet shows: the decoded base, no details.
  // (Built zeroed, not copied from the pyramid and cleared: a copy of every
  // detail is 40 MB on a 1.66 M-vertex mesh.)
  Pyramid coarse;
  coarse.hierarchy = out.pyramid.hierarchy;
  coarse.settings = out.pyramid.settings;
  coarse.base = out.base.positions;
  for (const auto& band : out.pyramid.subbands) {
    coarse.subbands.emplace_back(band.size(), Vec3::Zero());
  }
  const std::vector<Vec3> start = transform.Inverse(coarse);
  // Weighed as the packets' reductions are: the error along the encoded
  // surface's normal in full, the rest (a slide along the surface) by
  // 1 / tangent_step_scale^2.
  const std::vector<Vec3> normals =
      VertexNormals(h.faces(levels), out.mesh.positions, start.size());
  for (size_t v = 0; v < start.size(); ++v) {
    const Vec3 e = start[v] - out.mesh.positions[v];
    const double along = e.dot(normals[v]);
    out.zero_packet_distortion +=
        along * along + tangent_weight * (e.squaredNorm() - along * along);
  }
  return out;
}

double QuantizedComponent::SquaredError(size_t k, uint32_t mag, int n) const {
  const double r = (mag >> n) == 0 ? 0.0 : Dequantize(mag >> n, n, negative[k], step, xi0);
  return (value[k] - r) * (value[k] - r);
}

std::vector<double> SubbandComponent(const PreparedStream& prepared, int j, int c) {
  const auto& band = prepared.pyramid.subbands[static_cast<size_t>(j)];
  std::vector<double> values(band.size());
  for (size_t k = 0; k < band.size(); ++k) values[k] = band[k][c];
  return values;
}

QuantizedComponent QuantizeAtStep(std::vector<double> values, double step, double weight,
                                  double gain, int deadzone, double& energy) {
  QuantizedComponent q;
  q.value = std::move(values);
  q.step = step;
  q.weight = weight;
  q.xi0 = DeadzoneXi(deadzone);
  q.q0.reserve(q.value.size());
  q.negative.reserve(q.value.size());
  uint32_t max_q = 0;
  for (const double x : q.value) {
    q.q0.push_back(QuantizeMagnitude(x, q.step, q.xi0));
    q.negative.push_back(x < 0);
    max_q = std::max(max_q, q.q0.back());
    energy += q.weight * gain * x * x;
  }
  q.top = TopBitplane(max_q);
  return q;
}

QuantizedComponent QuantizeValues(const PreparedStream& prepared, int j, int c,
                                  std::vector<double> values, int deadzone, double& energy) {
  const double gain = prepared.gains.subband[static_cast<size_t>(j)];
  const double scale = c == 0 ? 1.0 : prepared.tangent_step_scale;
  return QuantizeAtStep(std::move(values), prepared.step0 / std::sqrt(gain) * scale,
                        1 / (scale * scale), gain, deadzone, energy);
}

void AppendQuantizer(const QuantizedComponent& q, int deadzone, proto::StreamHeader& header) {
  AppendQuantizer(q, deadzone, *header.mutable_quantizers());
}

void AppendQuantizer(const QuantizedComponent& q, int deadzone,
                     google::protobuf::RepeatedPtrField<proto::Quantizer>& out) {
  proto::Quantizer* pq = out.Add();
  pq->set_step(q.step);
  pq->set_deadzone(static_cast<uint32_t>(deadzone));
  pq->set_top_bitplane(q.top);
}

QuantizedComponent QuantizeComponent(PreparedStream& prepared, int j, int c,
                                     std::vector<double> values, int deadzone, double& energy) {
  QuantizedComponent q = QuantizeValues(prepared, j, c, std::move(values), deadzone, energy);
  AppendQuantizer(q, deadzone, prepared.header);
  return q;
}

}  // namespace meshwave
