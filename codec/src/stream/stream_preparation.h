// What every coder of a semi-regular mesh does before its bitplane passes:
// reorder the base for compact coding, transform, code the base mesh, and
// fill the header fields all coders share. SIM, 3xC and PGC start from the
// same preparation, so they code the very same quantised coefficients.
#ifndef MESHWAVE_STREAM_STREAM_PREPARATION_H_
#define MESHWAVE_STREAM_STREAM_PREPARATION_H_

#include "meshwave/encoder.h"
#include "quant/subband_gains.h"
#include "stream/base_mesh_codec.h"
#include "stream.pb.h"

namespace meshwave {

struct PreparedStream {
  SemiRegularMesh mesh;        // in the stream's vertex order
  proto::StreamHeader header;  // common fields and the base mesh; no coder
  TransformSettings transform;  // the options' transform, with its SAWT plan
  Pyramid pyramid;
  SubbandGains gains;
  DecodedBase base;            // the base mesh as a decoder will hold it
  double step0 = 0;            // diagonal * 2^-precision
  double base_distortion = 0;  // gain-weighted error of the decoded base
  // The true squared error of the mesh a decoder shows before any packet.
  double zero_packet_distortion = 0;
};

Result<PreparedStream> PrepareStream(const SemiRegularMesh& input,
                                     const EncodeOptions& options);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_STREAM_PREPARATION_H_
