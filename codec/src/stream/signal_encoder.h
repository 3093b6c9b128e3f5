// The coding of one per-vertex signal of three components on the
// semi-regular hierarchy: its wavelet subbands quantised per (subband,
// component) and coded bitplane by bitplane into packets. The geometry is
// one such signal; a channel (a vertex attribute such as colour) is
// another, coded by the same functions with its own steps.
#ifndef MESHWAVE_STREAM_SIGNAL_ENCODER_H_
#define MESHWAVE_STREAM_SIGNAL_ENCODER_H_

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bitplane/subband_layout.h"
#include "meshwave/encoder.h"
#include "stream.pb.h"
#include "stream/stream_preparation.h"

namespace meshwave {

// How a signal's coefficients are quantised: subband j, component c gets
// the step step0 / sqrt(gains[j]) * component_scale[c], and a unit of its
// squared error is worth 1 / component_scale[c]^2 in the signal's
// distortion (a coarser step for an error that counts less: equal slopes).
struct SignalScale {
  double step0 = 0;
  std::array<double, 3> component_scale{1, 1, 1};
  std::vector<double> gains;  // G_0 ... G_{J-1}, the subbands' synthesis gains
};

// The geometry's scale: the prepared stream's step0, its tangent step scale
// for components 1 and 2, and the subband gains.
SignalScale GeometryScale(const PreparedStream& prepared);

// Every (subband, component) of a signal quantised.
struct QuantizedSignal {
  std::vector<std::array<QuantizedComponent, 3>> subbands;
  std::vector<std::array<int, 3>> deadzones;  // the deadzone code of each
};

// Quantises `subbands` (d^0 ... d^{J-1}) with `scale`, each (subband,
// component) with the deadzone code `deadzone`, or the one
// ChooseDeadzoneCode picks from it when `auto_deadzone`. Adds each
// subband's weighted energy to energy[j] (the start of its distortion
// chain); energy has J entries. A task per subband on `threads`, the
// finest first; the result does not depend on the thread count.
QuantizedSignal QuantizeSignal(const std::vector<std::vector<Vec3>>& subbands,
                               const SignalScale& scale, int deadzone, bool auto_deadzone,
                               int threads, std::span<double> energy);

// The signal's quantizers, in (subband, component) order as a decoder
// reads them.
void AppendQuantizers(const QuantizedSignal& signal,
                      google::protobuf::RepeatedPtrField<proto::Quantizer>& out);

struct CodedPacket {
  std::string payload;
  double reduction = 0;  // of the signal's weighted squared error
};

struct CodedSignal {
  // Per subband, its packets from the top bitplane down.
  std::vector<std::vector<CodedPacket>> subbands;
  // Per subband, the bitplanes below which packets hold one codeword per
  // precinct (docs/FORMAT.md 2.2).
  std::vector<uint32_t> split_planes;
};

// Codes every packet of `signal` with the subbands' precinct layouts, the
// coder's contexts (3xC or SIM), splitting the low bitplanes of a subband
// where its precincts average at least `split_bytes_per_precinct` bytes a
// packet. Reductions are weighted by the scale's gains. A task per subband
// on `threads`; the bytes do not depend on the thread count.
CodedSignal CodeSignal(const QuantizedSignal& signal,
                       const std::vector<std::vector<SubbandLayout>>& layouts,
                       const SignalScale& scale, CoderKind coder,
                       uint32_t split_bytes_per_precinct, int threads);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_SIGNAL_ENCODER_H_
