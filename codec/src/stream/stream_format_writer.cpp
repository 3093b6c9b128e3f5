#include "stream/stream_format_writer.h"

#include "stream/stream_format.h"

namespace meshwave {

// The decoder library names this field without generated code.
static_assert(kHeaderPresentField == proto::StreamHeader::kPresentFieldNumber);

void ToProto(const StreamHeader::BaseMesh& base, proto::BaseMesh& out) {
  out.set_vertex_count(base.vertex_count);
  out.set_face_count(base.face_count);
  out.clear_origin();
  for (double o : base.origin) out.add_origin(o);
  out.set_step(base.step);
  out.set_coded(base.coded);
  out.set_refinement_planes(base.refinement_planes);
}

void ToProto(const StreamHeader::SawtChoices& sawt, proto::SawtChoices& out) {
  out.set_alpha(sawt.alpha);
  out.set_region_count(sawt.region_count);
  out.set_coded(sawt.coded);
  out.set_crc32c(sawt.crc32c);
}

Result<StreamHeader> ToStreamHeader(const proto::StreamHeader& header) {
  // Through the bytes, so that the stream's header is exactly what a
  // decoder reads (and its bytes_without_present are protobuf's).
  auto read = ReadStreamHeader(header.SerializeAsString());
  if (!read.ok()) {
    return InvalidArgument("the stream header does not read back (is the mesh name UTF-8?)");
  }
  return read;
}

}  // namespace meshwave
