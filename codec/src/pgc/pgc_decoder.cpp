#include <cmath>
#include <string>

#include "pgc/pgc_stream.h"
#include "quant/deadzone_quantizer.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "stream/sawt_field_decoder.h"
#include "stream/stream_format.h"

namespace meshwave {
namespace {

// The header checks that matter before anything is built from it: those
// of every stream, then PGC's coder and one-chain index.
Status ValidatePgcHeader(const StreamHeader& h) {
  MW_RETURN_IF_ERROR(ValidateVersionAndLevels(h));
  if (static_cast<int32_t>(h.coder) != kPgcCoderValue) {
    return ParseError("PGC header: coder " + std::to_string(static_cast<int32_t>(h.coder)) +
                      " is not PGC");
  }
  MW_RETURN_IF_ERROR(ValidateQuantizers(h));
  if (h.base.refinement_planes != 0) {
    return ParseError("PGC header: the base mesh has refinement planes (PGC sends it whole)");
  }
  int top = -1;
  for (const auto& q : h.quantizers) top = std::max(top, q.top_bitplane);
  return ValidateCompactIndex(h, top + 1, 1);
}

}  // namespace

std::vector<uint32_t> PgcPacketChains(const StreamHeader& header) {
  return std::vector<uint32_t>(header.packets.length.size(), 0);
}

Result<std::unique_ptr<PgcDecoder>> PgcDecoder::Create(
    const StreamHeader& header, const DecoderOptions& options) {
  MW_RETURN_IF_ERROR(ValidatePgcHeader(header));
  std::unique_ptr<PgcDecoder> d(new PgcDecoder());
  d->header_ = header;
  d->options_ = options;
  MW_RETURN_IF_ERROR(
      SetUpDecoder(header, options.max_base_vertices, d->base_, d->hierarchy_, d->transform_));
  const auto& h = *d->hierarchy_;
  const int levels = h.levels();
  for (int c = 0; c < 3; ++c) {
    std::vector<int> top(levels);
    for (int j = 0; j < levels; ++j) top[j] = header.quantizer(j, c).top_bitplane;
    d->states_[c].Init(h, top);
    d->top_ = std::max(d->top_, d->states_[c].top());
  }
  return d;
}

Status PgcDecoder::AddPacket(std::string_view payload) {
  if (broken_) {
    return InvalidArgument("PGC decoder is unusable after an earlier corrupt packet");
  }
  if (decoded_ >= packet_count()) {
    return InvalidArgument("PGC stream: all " + std::to_string(packet_count()) +
                           " packets were decoded already");
  }
  const int i = static_cast<int>(decoded_);
  const int b = top_ - i;
  const auto& index = header_.packets;
  const std::string what = "PGC packet " + std::to_string(i) + " (bitplane " +
                           std::to_string(b) + ")";
  if (payload.size() != index.length[decoded_]) {
    return ParseError(what + ": " + std::to_string(payload.size()) +
                      " bytes, index says " + std::to_string(index.length[decoded_]));
  }
  if (!PacketCheckMatches(index, static_cast<uint32_t>(i), payload)) {
    return ParseError(what + ": CRC-16 check mismatch (corrupt payload)");
  }
  ArithmeticDecoder dec(payload);
  ZerotreeDecoderIo io(dec);
  for (ZerotreeState& s : states_) {
    if (b > s.top()) continue;
    ZerotreeContexts contexts;
    CodeZerotreeBitplane(*hierarchy_, s, b, contexts, io);
  }
  if (dec.overrun()) {
    broken_ = true;
    return ParseError(what + ": payload ends before its symbols (corrupt stream)");
  }
  ++decoded_;
  return Status::Ok();
}

std::vector<Vec3> PgcDecoder::Positions() const {
  const auto& h = *hierarchy_;
  Pyramid p;
  p.hierarchy = hierarchy_;
  p.base = base_.positions;
  p.subbands.resize(h.levels());
  for (int j = 0; j < h.levels(); ++j) p.subbands[j].assign(h.subband_size(j), Vec3::Zero());
  for (int c = 0; c < 3; ++c) {
    const ZerotreeState& s = states_[c];
    const int n = s.known_from();
    for (const TreeNode& node : s.lsp()) {
      const StreamHeader::Quantizer& q = header_.quantizer(node.j, c);
      p.subbands[node.j][node.k][c] =
          Dequantize(s.mag(node.j)[node.k] >> n, n, s.negative(node.j)[node.k], q.step,
                     DeadzoneXi(static_cast<int>(q.deadzone)), options_.gamma);
    }
  }
  return transform_->Inverse(p);
}

}  // namespace meshwave
