#include "stream/decoder_setup.h"

#include <cmath>
#include <string>

#include "meshwave/stream_limits.h"
#include "quant/deadzone_quantizer.h"
#include "stream/sawt_field_decoder.h"
#include "stream/stream_format.h"

namespace meshwave {

Status ValidateVersionAndLevels(const StreamHeader& h) {
  MW_RETURN_IF_ERROR(CheckFormatVersion(h).WithContext("stream"));
  const uint32_t levels = h.transform.levels;
  if (levels > kMaxStreamLevels) {
    return ParseError("header: " + std::to_string(levels) + " levels (at most " +
                      std::to_string(kMaxStreamLevels) + ")");
  }
  return Status::Ok();
}

namespace {

// `owner` names whose quantizers these are in messages ("" for the
// geometry's).
Status CheckQuantizers(const std::vector<StreamHeader::Quantizer>& quantizers, uint32_t levels,
                       const std::string& owner) {
  if (quantizers.size() != 3 * static_cast<size_t>(levels)) {
    return ParseError("header: " + owner + std::to_string(quantizers.size()) +
                      " quantizers for " + std::to_string(levels) + " subbands");
  }
  for (const auto& q : quantizers) {
    if (!(q.step > 0) || !std::isfinite(q.step) || q.deadzone > 3 || q.top_bitplane < -1 ||
        q.top_bitplane > kMaxBitplane) {
      return ParseError("header: " + owner + "a quantizer is out of range");
    }
  }
  return Status::Ok();
}

}  // namespace

Status ValidateQuantizers(const StreamHeader& h) {
  return CheckQuantizers(h.quantizers, h.transform.levels, "");
}

Status ValidateChannels(const StreamHeader& h) {
  if (h.channels.size() > kMaxChannels) {
    return ParseError("header: " + std::to_string(h.channels.size()) + " channels (at most " +
                      std::to_string(kMaxChannels) + ", one of each kind)");
  }
  for (size_t k = 0; k < h.channels.size(); ++k) {
    const StreamHeader::Channel& channel = h.channels[k];
    const std::string owner = "channel " + std::to_string(k) + ": ";
    if (channel.kind != StreamChannelKind::kColor) {
      return ParseError("header: " + owner + "unknown kind " +
                        std::to_string(static_cast<int32_t>(channel.kind)) +
                        " (this build knows 1, colour)");
    }
    for (size_t other = 0; other < k; ++other) {
      if (h.channels[other].kind == channel.kind) {
        return ParseError("header: " + owner + "a second channel of the same kind");
      }
    }
    MW_RETURN_IF_ERROR(CheckQuantizers(channel.quantizers, h.transform.levels, owner));
    if (!(channel.base_step > 0) || !std::isfinite(channel.base_step)) {
      return ParseError("header: " + owner + "base step not finite and positive");
    }
    if (!(channel.rd_weight > 0) || !std::isfinite(channel.rd_weight)) {
      return ParseError("header: " + owner + "rd weight not finite and positive");
    }
    // 3 varints of 1 to 5 bytes per base vertex (DecodeChannelBase reads
    // them once the base mesh is decoded).
    const uint64_t values = 3 * uint64_t{h.base.vertex_count};
    if (channel.base.size() < values || channel.base.size() > 5 * values) {
      return ParseError("header: " + owner + std::to_string(channel.base.size()) +
                        " bytes of base values for " + std::to_string(h.base.vertex_count) +
                        " base vertices (3 varints each)");
    }
  }
  return Status::Ok();
}

Result<TransformSettings> SetUpHierarchy(const StreamHeader& header, uint32_t max_base_vertices,
                                         DecodedBase& base,
                                         std::shared_ptr<const SemiRegularHierarchy>& hierarchy) {
  MW_ASSIGN_OR_RETURN(TransformSettings settings, ReadTransformSettings(header.transform));
  MW_ASSIGN_OR_RETURN(base, DecodeBaseMesh(header.base, max_base_vertices));
  const int levels = static_cast<int>(header.transform.levels);
  auto built = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                           base.faces, levels);
  if (!built.ok()) return built.status().WithContext("stream base mesh");
  hierarchy = *built;
  const auto& h = *hierarchy;
  if (header.vertices != h.vertex_count(levels) || header.faces != h.faces(levels).size()) {
    return ParseError("header: vertex or face count does not match the hierarchy");
  }
  if (header.bbox_min.size() != 3 || header.bbox_max.size() != 3) {
    return ParseError("header: bounding box needs 3 coordinates");
  }
  if (settings.predictor == Predictor::kSawt) {
    MW_ASSIGN_OR_RETURN(settings.sawt, DecodeSawtChoices(*header.transform.sawt, h, base.grid));
  }
  return settings;
}

Status SetUpDecoder(const StreamHeader& header, uint32_t max_base_vertices, DecodedBase& base,
                    std::shared_ptr<const SemiRegularHierarchy>& hierarchy,
                    std::unique_ptr<WaveletTransform>& transform) {
  MW_ASSIGN_OR_RETURN(TransformSettings settings,
                      SetUpHierarchy(header, max_base_vertices, base, hierarchy));
  MW_ASSIGN_OR_RETURN(WaveletTransform t, WaveletTransform::Create(hierarchy, settings));
  transform = std::make_unique<WaveletTransform>(std::move(t));
  return Status::Ok();
}

}  // namespace meshwave
