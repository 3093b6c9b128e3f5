// Lifting wavelet transforms of semi-regular meshes (Sweldens 1998; Satti et al.
// 2011).
//
// Forward, for j = J-1 down to 0, in place on the level-ordered positions:
//   predict  d^j_k = c^{j+1}_k - P_k(c^j)        (P reads level-j vertices only)
//   update   c^j_a += w_a d^j_k, c^j_b += w_b d^j_k  (lifted transforms only)
//   frame    d^j_k expressed as (normal, tangent1, tangent2) in a frame made
//            from the updated c^j, i.e. from what the decoder holds then.
// Inverse runs the same steps backwards with opposite signs, so every
// transform is perfectly invertible up to floating-point rounding.
#ifndef MESHWAVE_WAVELET_H_
#define MESHWAVE_WAVELET_H_

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

enum class Predictor {
  kLinear,     // midpoint of the split edge
  kButterfly,  // Zorin's modified butterfly: 8-point rule, extraordinary
               // and boundary rules (Zorin et al. 1996)
  kLoop,       // Loop's edge mask 3/8, 3/8, 1/8, 1/8; midpoint on boundaries
  kSawt,       // spatially adaptive (Denis et al. 2010a): one of the filters f1..f6
               // per (level, region), TransformSettings::sawt says which
};

// The SAWT's regions and filter choices (wavelet/sawt_plan.h).
struct SawtPlan;

enum class UpdateWeights {
  kNone,      // unlifted: coarse levels are plain subsamples
  kConstant,  // w = 1/8 per endpoint
  kValence,   // w_a = n_f(k) / (8 n_f(a)), zero-moment rule (docs/CODEC.md)
};

enum class FrameMode {
  kGlobal,  // coefficients stay in x, y, z
  kLocal,   // normal and two tangents from the coarser level (default)
};

struct TransformSettings {
  TransformSettings() = default;
  TransformSettings(Predictor p, UpdateWeights u, FrameMode f,
                    std::shared_ptr<const SawtPlan> plan = nullptr)
      : predictor(p), update(u), frames(f), sawt(std::move(plan)) {}

  Predictor predictor = Predictor::kButterfly;
  UpdateWeights update = UpdateWeights::kConstant;
  FrameMode frames = FrameMode::kLocal;
  // Required with Predictor::kSawt, ignored otherwise. The encoder chooses
  // it (ChooseSawtFilters), a decoder reads it from the stream header.
  std::shared_ptr<const SawtPlan> sawt;
};

// Names as used on the command line and in the stream header:
// "linear", "butterfly", "loop", "sawt" plus "lifted"/"unlifted"; e.g. "butterfly".
Result<Predictor> ParsePredictor(const std::string& name);
const char* PredictorName(Predictor predictor);
Result<UpdateWeights> ParseUpdateWeights(const std::string& name);
const char* UpdateWeightsName(UpdateWeights update);

// The wavelet decomposition of a semi-regular mesh: base positions c^0 and
// one subband per level. Subband d^j has one 3-vector per edge of M^j (in the
// edge order of the hierarchy): components (normal, tangent1, tangent2) with
// local frames, (x, y, z) otherwise. Coefficient k of d^j has parent
// hierarchy->Parent(j, k) in d^{j-1} and children hierarchy->Children(j, k).
struct Pyramid {
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  TransformSettings settings;
  std::vector<Vec3> base;
  std::vector<std::vector<Vec3>> subbands;  // d^0 .. d^{J-1}

  int levels() const { return static_cast<int>(subbands.size()); }
};

// A transform bound to one hierarchy: the prediction stencils and update
// weights of every level are computed once, then Forward and Inverse are
// tight loops. Thread-safe for concurrent const calls.
class WaveletTransform {
 public:
  // When Create builds the stencils: every level's now, or level 0's now
  // (it checks the base mesh) and each finer level's on its first use, by
  // whichever call needs it first (once, safe from several threads). The
  // finest level's stencils are about three quarters of the work: a
  // decoder that draws a coarser mesh never builds them.
  enum class Stencils { kAllNow, kOnFirstUse };
  static Result<WaveletTransform> Create(
      std::shared_ptr<const SemiRegularHierarchy> hierarchy,
      const TransformSettings& settings, Stencils when = Stencils::kAllNow);

  // positions: the V_J positions of the finest level in canonical order.
  // The analysis is the encoder's: defined in meshwave_codec
  // (wavelet/wavelet_forward.cpp), not in the decoder library.
  Pyramid Forward(std::span<const Vec3> positions) const;
  // The same into an existing pyramid, reusing its memory.
  void Forward(std::span<const Vec3> positions, Pyramid& out) const;

  // Reconstructs M^max_level (max_level in [0, levels()]; -1 or beyond:
  // levels()): returns its V_max_level positions. Subbands finer than
  // max_level are not read.
  std::vector<Vec3> Inverse(const Pyramid& pyramid, int max_level = -1) const;
  // The same into `out`, reusing its memory.
  void Inverse(const Pyramid& pyramid, int max_level,
               std::vector<Vec3>& out) const;

  // The same in place: x holds c^0 in [0, V_0) and each subband d^j (j <
  // max_level) where level j+1's new vertices go, [V_j, V_{j+1}); it is
  // resized to V_max_level and ends holding M^max_level. What a decoder
  // that dequantises straight into x needs: no pyramid to fill and copy.
  void InverseInPlace(std::vector<Vec3>& x, int max_level = -1) const;

  // Applies the prediction of level j+1 from the first V_j positions of
  // `positions` and writes the predicted odd vertices (subdivision with zero
  // detail). `positions` must hold V_{j+1} entries.
  void PredictLevel(int j, std::span<Vec3> positions) const;

  // Builds level j's stencils now unless they are built (j in [0, J)):
  // for a caller that builds ahead of use on a thread of its own.
  void PrepareLevel(int j) const;

  const SemiRegularHierarchy& hierarchy() const { return *hierarchy_; }
  // J.
  int levels() const;
  const TransformSettings& settings() const { return settings_; }

  struct Level;       // stencils and update weights of one level (private)
  class LevelTable;   // every level's, each built once (private)

 private:
  std::shared_ptr<const SemiRegularHierarchy> hierarchy_;
  TransformSettings settings_;
  std::shared_ptr<const LevelTable> levels_;
};

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_H_
