// The decoding side of the original layer (docs/FORMAT.md 2.5): the
// connectivity packet, then the positions packets coarse to fine, into the
// user's own mesh. ProgressiveDecoder holds one when the stream has the
// layer and hands it the layer's packets.
#ifndef MESHWAVE_STREAM_ORIGINAL_LAYER_DECODER_H_
#define MESHWAVE_STREAM_ORIGINAL_LAYER_DECODER_H_

#include <optional>
#include <string_view>

#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "original/original_positions.h"
#include "original/original_traversal.h"

namespace meshwave::original {

class LayerDecoder {
 public:
  // `layer` validated (ValidateOriginal).
  explicit LayerDecoder(const StreamHeader::Original& layer) : layer_(layer) {}
  // The positions decoder refers to the traversal inside.
  LayerDecoder(const LayerDecoder&) = delete;
  LayerDecoder& operator=(const LayerDecoder&) = delete;

  // Part 0 (the connectivity) or part k >= 1 (positions payload k - 1),
  // each after the one before (the caller checks the order). Untrusted
  // bytes: damage is a kParseError, after which only Reset is of use.
  Status Add(int part, std::string_view payload);

  // Whether the mesh can be given: connectivity and coarse positions held.
  bool ready() const { return positions_ && positions_->held() > 0; }
  // The original's faces over its vertex ids and its positions as the
  // parts held place them (the middle of their cells). Empty when not
  // ready.
  TriMesh Mesh() const;

  void Reset() {
    positions_.reset();
    traversal_.reset();
  }

 private:
  StreamHeader::Original layer_;
  std::optional<Traversal> traversal_;
  // Holds a reference to *traversal_: reset before it.
  std::optional<PositionsDecoder> positions_;
};

}  // namespace meshwave::original

#endif  // MESHWAVE_STREAM_ORIGINAL_LAYER_DECODER_H_
