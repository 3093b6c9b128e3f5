// What every coder of a semi-regular mesh does before its bitplane passes:
// reorder the base for compact coding, transform, code the base mesh, and
// fill the header fields all coders share. SIM, 3xC and PGC start from the
// same preparation, so they code the very same quantised coefficients.
#ifndef MESHWAVE_STREAM_STREAM_PREPARATION_H_
#define MESHWAVE_STREAM_STREAM_PREPARATION_H_

#include "meshwave/encoder.h"
#include "quant/subband_gains.h"
#include "stream.pb.h"
#include "stream/base_mesh_decoder.h"
#include "stream/base_mesh_encoder.h"

namespace meshwave {

struct PreparedStream {
  SemiRegularMesh mesh;        // in the stream's vertex order
  // Each of its vertices' index in the input mesh (attributes follow it).
  std::vector<uint32_t> input_vertex;
  proto::StreamHeader header;  // common fields and the base mesh; no coder
  TransformSettings transform;  // the options' transform, with its SAWT plan
  Pyramid pyramid;
  SubbandGains gains;
  // The base mesh as a decoder holding no packet has it (coarse grid, no
  // refinement).
  DecodedBase base;
  // What the base refinement packets carry (EncodedBaseMesh::residual), and
  // the gain-weighted error of the base with the m lowest bits of every
  // coordinate missing, m = 0 ... R (base_error[R]: no refinement packet).
  std::vector<IntVec3> base_residual;
  std::vector<double> base_error;
  double step0 = 0;            // diagonal * 2^-precision
  // Step of the tangential components over the normal one's (1 with global
  // frames, whose components are x, y, z).
  double tangent_step_scale = 1;
  // Gain-weighted error of the fully refined base (base_error[0]).
  double base_distortion = 0;
  // The true squared error of the mesh a decoder shows before any packet,
  // its tangential part (off the encoded surface's vertex normals) weighed
  // by 1 / tangent_step_scale^2 as the packets' reductions are.
  double zero_packet_distortion = 0;
};

Result<PreparedStream> PrepareStream(const SemiRegularMesh& input,
                                     const EncodeOptions& options);

// The largest R (at most kMaxBaseRefinementPlanes) whose coarse base code
// plus R refinement packets (and their 5 bytes of index each) take at most
// 2 % more bytes than the whole base coded in the header: R from which on
// the dropped bits are noise that no prediction removes. Positions and
// faces as EncodeBaseMesh takes them.
Result<uint32_t> ChooseBaseRefinementPlanes(const std::vector<Vec3>& positions,
                                            const std::vector<Face>& faces, double step);

// The quantised coefficients of one (subband, component).
struct QuantizedComponent {
  std::vector<double> value;      // the coefficients
  std::vector<uint32_t> q0;       // magnitudes at bitplane 0
  std::vector<uint8_t> negative;  // signs
  double step = 0;
  double xi0 = 0;  // the deadzone's reconstruction offset
  // What a unit of this component's squared error is worth in the
  // distortion the packet order minimises: 1 / tangent_step_scale^2 for
  // the tangential components, 1 otherwise (a coarser step is the right
  // one for an error that counts less, at equal slope).
  double weight = 1;
  int top = -1;    // highest bitplane of any magnitude, -1 when all are 0
  // Squared error of value[k] once its magnitude `mag` is known from
  // bitplane n up (0 when nothing is known yet).
  double SquaredError(size_t k, uint32_t mag, int n) const;
};

// Component c (0 = x, 1 = y, 2 = z with global frames; 0 = normal, 1 and 2
// = tangents with local frames) of subband j of the pyramid.
std::vector<double> SubbandComponent(const PreparedStream& prepared, int j, int c);

// Quantises `values`, component c of subband j, with the step
// step0 / sqrt(G_j) (times tangent_step_scale for a tangential component)
// and deadzone code `deadzone` (docs/FORMAT.md), appends that quantizer to
// the header and adds the values' weighted energy weight G_j x^2 to
// `energy` (the start of their distortion chain). Every coder quantises
// through this.
QuantizedComponent QuantizeComponent(PreparedStream& prepared, int j, int c,
                                     std::vector<double> values, int deadzone, double& energy);

// QuantizeComponent in two halves, for coders that quantise subbands on
// several threads: the quantisation (reads `prepared` only; adds to
// `energy`), and the quantizer's entry in the header (in (subband,
// component) order, as the decoder reads them).
QuantizedComponent QuantizeValues(const PreparedStream& prepared, int j, int c,
                                  std::vector<double> values, int deadzone, double& energy);
void AppendQuantizer(const QuantizedComponent& q, int deadzone, proto::StreamHeader& header);
void AppendQuantizer(const QuantizedComponent& q, int deadzone,
                     google::protobuf::RepeatedPtrField<proto::Quantizer>& out);

// What every quantisation above comes down to, for any signal: `values`
// with `step` and deadzone code `deadzone`; a unit of squared error is
// worth `weight` (QuantizedComponent::weight), and `energy` grows by
// weight * gain * x^2 per value x (gain: the subband's synthesis gain).
QuantizedComponent QuantizeAtStep(std::vector<double> values, double step, double weight,
                                  double gain, int deadzone, double& energy);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_STREAM_PREPARATION_H_
