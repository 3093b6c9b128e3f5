#include <cmath>
#include <string>

#include "quant/deadzone_quantizer.h"
#include "stream/packet_index.h"
#include "stream/pgc_stream.h"
#include "stream/sawt_field.h"
#include "stream/stream_format.h"

namespace meshwave {
namespace {

// The header checks that matter before anything is built from it.
Status ValidatePgcHeader(const StreamHeader& h) {
  if (h.format_version != kFormatVersion) {
    return Status(StatusCode::kUnsupported,
                  "PGC header: format version " + std::to_string(h.format_version));
  }
  if (static_cast<int32_t>(h.coder) != kPgcCoderValue) {
    return ParseError("PGC header: coder " + std::to_string(static_cast<int32_t>(h.coder)) +
                      " is not PGC");
  }
  const uint32_t levels = h.transform.levels;
  if (levels > 12) {
    return ParseError("PGC header: " + std::to_string(levels) + " levels (at most 12)");
  }
  if (h.quantizers.size() != 3 * static_cast<size_t>(levels)) {
    return ParseError("PGC header: " + std::to_string(h.quantizers.size()) +
                      " quantizers for " + std::to_string(levels) + " subbands");
  }
  int top = -1;
  for (const auto& q : h.quantizers) {
    if (!(q.step > 0) || !std::isfinite(q.step) || q.deadzone > 3 || q.top_bitplane < -1 ||
        q.top_bitplane > kMaxBitplane) {
      return ParseError("PGC header: a quantizer is out of range");
    }
    top = std::max(top, q.top_bitplane);
  }
  MW_RETURN_IF_ERROR(ValidateCompactIndex(h, top + 1, 1));
  if (h.bbox_min.size() != 3 || h.bbox_max.size() != 3) {
    return ParseError("PGC header: bounding box needs 3 coordinates");
  }
  return Status::Ok();
}

}  // namespace

Result<std::unique_ptr<PgcDecoder>> PgcDecoder::Create(
    const StreamHeader& header, const DecoderOptions& options) {
  MW_RETURN_IF_ERROR(ValidatePgcHeader(header));
  std::unique_ptr<PgcDecoder> d(new PgcDecoder());
  d->header_ = header;
  d->options_ = options;
  MW_ASSIGN_OR_RETURN(TransformSettings settings, ReadTransformSettings(header.transform));
  MW_ASSIGN_OR_RETURN(d->base_, DecodeBaseMesh(header.base, options.max_base_vertices));
  const int levels = static_cast<int>(header.transform.levels);
  auto hierarchy = SemiRegularHierarchy::Build(
      static_cast<uint32_t>(d->base_.positions.size()), d->base_.faces, levels);
  if (!hierarchy.ok()) return hierarchy.status().WithContext("PGC base mesh");
  d->hierarchy_ = *hierarchy;
  const auto& h = *d->hierarchy_;
  if (header.vertices != h.vertex_count(levels) || header.faces != h.faces(levels).size()) {
    return ParseError("PGC header: vertex or face count does not match the hierarchy");
  }
  if (settings.predictor == Predictor::kSawt) {
    MW_ASSIGN_OR_RETURN(settings.sawt,
                        DecodeSawtChoices(*header.transform.sawt, h, d->base_.grid));
  }
  MW_ASSIGN_OR_RETURN(WaveletTransform t, WaveletTransform::Create(d->hierarchy_, settings));
  d->transform_ = std::make_unique<WaveletTransform>(std::move(t));
  for (int c = 0; c < 3; ++c) {
    std::vector<int> top(levels);
    for (int j = 0; j < levels; ++j) top[j] = header.quantizers[static_cast<size_t>(3 * j + c)].top_bitplane;
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
      const StreamHeader::Quantizer& q = header_.quantizers[3 * static_cast<size_t>(node.j) + static_cast<size_t>(c)];
      p.subbands[node.j][node.k][c] =
          Dequantize(s.mag(node.j)[node.k] >> n, n, s.negative(node.j)[node.k], q.step,
                     DeadzoneXi(static_cast<int>(q.deadzone)), options_.gamma);
    }
  }
  return transform_->Inverse(p);
}

}  // namespace meshwave
