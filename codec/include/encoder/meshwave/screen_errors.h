// How far the stream's mesh still is from the complete remesh along the
// uniform rd order and bitplane by bitplane, measured in each precinct:
// what a view with a screen-space error (RegionOrder,
// Region::screen_error_px) judges units by when the server has measured
// it, instead of a bound. Each precinct stops at its own point of either
// sequence: where the view sees it coarse, early; where it sees it large,
// late. Measured by decoding, so the base mesh's error and what the
// transform carries from level to level are in it.
#ifndef MESHWAVE_SCREEN_ERRORS_H_
#define MESHWAVE_SCREEN_ERRORS_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meshwave/region_order.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

class StreamScreenErrors {
 public:
  // `payloads[id]`: every packet of `header` (validated); `precincts` of the
  // same header. Decodes the stream once per packet of the remesh and once
  // per bitplane (about a second for a mesh of 100 k vertices).
  static Result<StreamScreenErrors> Measure(const StreamHeader& header,
                                            std::span<const std::string_view> payloads,
                                            const StreamPrecincts& precincts);

  // The subbands measured; errors are kept per precinct of the finest one.
  int levels() const { return static_cast<int>(ancestor_.size()); }
  uint32_t finest_precincts() const { return finest_count_; }
  // The remesh's packets in the rd order (PacketOrder, Progression::kRd):
  // steps() of them; state k holds the first k.
  int steps() const { return static_cast<int>(error_.size()) - 1; }
  // Packet id's place in that order (state Rank + 1 is the first that holds
  // it); -1 for a packet not in it (texture, channel, original layer).
  int Rank(uint32_t id) const { return id < rank_.size() ? rank_[id] : -1; }
  // The largest distance, along the complete remesh's vertex normals,
  // between it and state k or any later state, over the finest vertices in
  // the base faces of finest precinct q (k in [0, steps()]).
  double Error(int k, uint32_t q) const { return error_[static_cast<size_t>(k)][q]; }
  // The same along bitplanes: state b holds every detail packet of
  // bitplane >= b and every base refinement plane >= b (b in [0,
  // planes()]; planes(): the header's base mesh alone); the largest
  // distance in state b or any state of more planes.
  int planes() const { return static_cast<int>(plane_error_.size()) - 1; }
  double PlaneError(int b, uint32_t q) const {
    return plane_error_[static_cast<size_t>(b)][q];
  }
  // The precinct of subband j that finest precinct q lies in.
  uint32_t Ancestor(int j, uint32_t q) const {
    return ancestor_[static_cast<size_t>(j)][q];
  }

 private:
  std::vector<std::vector<float>> error_;  // [k][q], non-increasing in k
  std::vector<std::vector<float>> plane_error_;  // [b][q], non-decreasing in b
  std::vector<int> rank_;                  // [id]
  std::vector<std::vector<uint32_t>> ancestor_;  // [j][q]
  uint32_t finest_count_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_SCREEN_ERRORS_H_
