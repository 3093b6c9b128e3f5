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

Status ValidateQuantizers(const StreamHeader& h) {
  const uint32_t levels = h.transform.levels;
  if (h.quantizers.size() != 3 * static_cast<size_t>(levels)) {
    return ParseError("header: " + std::to_string(h.quantizers.size()) +
                      " quantizers for " + std::to_string(levels) + " subbands");
  }
  for (const auto& q : h.quantizers) {
    if (!(q.step > 0) || !std::isfinite(q.step) || q.deadzone > 3 || q.top_bitplane < -1 ||
        q.top_bitplane > kMaxBitplane) {
      return ParseError("header: a quantizer is out of range");
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
