// How far the stream's mesh still is from the complete remesh along the
// uniform rd order and bitplane by bitplane, measured in each precinct:
// what a view with a screen-space error (RegionOrder,
// Region::screen_error_px) judges units by when the server has measured
// it, instead of a bound. Kept per base face, finer than the precincts, so
// that a view judges each part of a precinct at its own depth; each
// precinct then stops at its own point of either sequence: where the view
// sees it coarse, early; where it sees it large, late. Measured by decoding, so the base mesh's error and what the
// transform carries from level to level are in it.
#ifndef MESHWAVE_SCREEN_ERRORS_H_
#define MESHWAVE_SCREEN_ERRORS_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meshwave/mesh.h"
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

  // The subbands measured.
  int levels() const { return static_cast<int>(ancestor_.size()); }
  uint32_t finest_precincts() const { return finest_count_; }
  // Errors are kept per cluster: the finest vertices of one base face.
  uint32_t clusters() const { return static_cast<uint32_t>(cluster_precinct_.size()); }
  // The ball around cluster c's vertices in the complete remesh.
  const Vec3& centre(uint32_t c) const { return centre_[c]; }
  double radius(uint32_t c) const { return radius_[c]; }
  // The finest precinct cluster c lies in.
  uint32_t Precinct(uint32_t c) const { return cluster_precinct_[c]; }
  // The finest precincts, other than c's own, of the clusters whose base
  // faces share a vertex with c's: the vertices near c's border move with
  // their coefficients too.
  std::span<const uint32_t> NeighbourPrecincts(uint32_t c) const {
    return {neighbours_.data() + neighbour_first_[c], neighbours_.data() + neighbour_first_[c + 1]};
  }
  // The remesh's packets in the rd order (PacketOrder, Progression::kRd):
  // steps() of them; state k holds the first k.
  int steps() const { return steps_; }
  // Packet id's place in that order (state Rank + 1 is the first that holds
  // it); -1 for a packet not in it (texture, channel, original layer).
  int Rank(uint32_t id) const { return id < rank_.size() ? rank_[id] : -1; }
  // The largest distance, along the complete remesh's vertex normals,
  // between it and state k or any later state, over cluster c's vertices
  // (k in [0, steps()]).
  double Error(int k, uint32_t c) const {
    return error_[static_cast<size_t>(c) * static_cast<size_t>(steps_ + 1) + static_cast<size_t>(k)];
  }
  // The same along bitplanes: state b holds every detail packet of
  // bitplane >= b and every base refinement plane >= b (b in [0,
  // planes()]; planes(): the header's base mesh alone); the largest
  // distance in state b or any state of more planes.
  int planes() const { return planes_; }
  double PlaneError(int b, uint32_t c) const {
    return plane_error_[static_cast<size_t>(c) * static_cast<size_t>(planes_ + 1) + static_cast<size_t>(b)];
  }
  // The precinct of subband j that finest precinct q lies in.
  uint32_t Ancestor(int j, uint32_t q) const {
    return ancestor_[static_cast<size_t>(j)][q];
  }

 private:
  // Cluster by cluster (a request's bisections stay in one cache line or
  // two): [c][k], non-increasing in k; [c][b], non-decreasing in b.
  std::vector<float> error_, plane_error_;
  int steps_ = 0, planes_ = 0;
  std::vector<Vec3> centre_;                     // [c]
  std::vector<double> radius_;                   // [c]
  std::vector<uint32_t> cluster_precinct_;       // [c]
  std::vector<uint32_t> neighbour_first_, neighbours_;
  std::vector<int> rank_;                  // [id]
  std::vector<std::vector<uint32_t>> ancestor_;  // [j][q]
  uint32_t finest_count_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_SCREEN_ERRORS_H_
