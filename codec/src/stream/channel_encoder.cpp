#include "stream/channel_encoder.h"

#include <cmath>
#include <limits>
#include <string>

#include "attributes/ycocg.h"

namespace meshwave {

namespace {

// Zigzag varints (FORMAT.md 2.3), vertex by vertex.
std::string BaseValues(const std::vector<Vec3>& base, double step) {
  std::string out;
  for (const Vec3& v : base) {
    for (int c = 0; c < 3; ++c) {
      const auto q = static_cast<int64_t>(std::llround(v[c] / step));
      uint64_t u = q < 0 ? 2 * static_cast<uint64_t>(-q) - 1 : 2 * static_cast<uint64_t>(q);
      while (u >= 0x80) {
        out.push_back(static_cast<char>((u & 0x7f) | 0x80));
        u >>= 7;
      }
      out.push_back(static_cast<char>(u));
    }
  }
  return out;
}

}  // namespace

Result<EncodedChannel> EncodeColorChannel(const PreparedStream& prepared,
                                          const SemiRegularMesh& mesh,
                                          const std::vector<Vec3>& colors,
                                          const std::vector<std::vector<SubbandLayout>>& layouts,
                                          const EncodeOptions& options) {
  const SemiRegularHierarchy& h = *mesh.hierarchy;
  const int levels = h.levels();
  if (colors.size() != h.vertex_count(levels)) {
    return InvalidArgument(std::to_string(colors.size()) + " vertex colours for a mesh of " +
                           std::to_string(h.vertex_count(levels)) + " vertices");
  }
  if (options.color_precision < 4 || options.color_precision > 20) {
    return InvalidArgument("colour precision must be in [4, 20]");
  }
  if (!(options.color_rd_weight > 0) || !std::isfinite(options.color_rd_weight)) {
    return InvalidArgument("the colour channel's rd weight must be finite and positive");
  }
  std::vector<Vec3> ycocg(colors.size());
  for (size_t v = 0; v < colors.size(); ++v) {
    if (!colors[v].allFinite()) {
      return InvalidArgument("vertex colour " + std::to_string(v) + " is not finite");
    }
    ycocg[v] = RgbToYCoCg(colors[v]);
  }
  // The geometry's predictor and update (and SAWT choices); local frames
  // belong to positions only.
  TransformSettings settings = prepared.transform;
  settings.frames = FrameMode::kGlobal;
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(mesh.hierarchy, settings));
  const Pyramid pyramid = transform.Forward(ycocg);

  EncodedChannel out;
  out.header.set_kind(proto::CHANNEL_COLOR);
  // Squared RGB error from errors in Y, Co, Cg (YCoCgToRgb): 3 eY² +
  // 2 eCo² + 3 eCg². Steps scaled by 1 / sqrt of those weights give every
  // component the same slope.
  SignalScale scale;
  scale.step0 = std::ldexp(1.0, -options.color_precision);
  scale.component_scale = {1 / std::sqrt(3.0), 1 / std::sqrt(2.0), 1 / std::sqrt(3.0)};
  scale.gains = prepared.gains.subband;
  // The base values on the finest Y step a base vertex's gain calls for:
  // a few hundred values, two bytes each, cheaper than packets for them.
  const double base_step = scale.step0 / std::sqrt(3 * prepared.gains.base);
  out.header.set_base_step(base_step);
  out.header.set_base(BaseValues(pyramid.base, base_step));
  out.header.set_rd_weight(options.color_rd_weight);
  out.chain_start.assign(static_cast<size_t>(levels), 0.0);
  const QuantizedSignal quantized =
      QuantizeSignal(pyramid.subbands, scale, options.deadzone, options.auto_deadzone,
                     options.threads, out.chain_start);
  AppendQuantizers(quantized, *out.header.mutable_quantizers());
  // Never split: regions do not refine channels yet.
  out.coded = CodeSignal(quantized, layouts, scale, options.coder,
                         std::numeric_limits<uint32_t>::max(), options.threads);
  return out;
}

}  // namespace meshwave
