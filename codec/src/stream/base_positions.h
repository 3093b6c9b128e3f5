// The base mesh's positions (docs/FORMAT.md 3.2): each vertex's grid
// position predicted from the vertices before it, the residual coded with
// signed adaptive Golomb codes. What the encoder (base_mesh_encoder.h) and
// the decoder (base_mesh_decoder.h) must agree on: the prediction and its
// contexts.
#ifndef MESHWAVE_STREAM_BASE_POSITIONS_H_
#define MESHWAVE_STREAM_BASE_POSITIONS_H_

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "core/edge_key.h"
#include "entropy/adaptive_golomb.h"
#include "meshwave/mesh.h"

namespace meshwave {

// Contexts of the position code.
struct PositionContexts {
  SignedGolombContexts residual[3];
};

// The prediction of vertex v's grid position from vertices < v: across an
// edge of the face where v first appears (parallelogram), else the mean of
// that face's known corners, else the previous vertex.
class PositionPredictor {
 public:
  PositionPredictor(const std::vector<Face>& faces, uint32_t vertex_count)
      : faces_(faces), first_face_(vertex_count, kNoFace) {
    for (uint32_t f = 0; f < faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = faces[f][c];
        if (first_face_[v] == kNoFace) first_face_[v] = f;
        auto [it, fresh] = edge_faces_.try_emplace(
            EdgeKey(v, faces[f][(c + 1) % 3]), std::array<uint32_t, 2>{kNoFace, kNoFace});
        (it->second[0] == kNoFace ? it->second[0] : it->second[1]) = f;
      }
    }
  }

  IntVec3 Predict(uint32_t v, const std::vector<IntVec3>& grid) const {
    const uint32_t f = first_face_[v];
    uint32_t known[2];
    int n = 0;
    if (f != kNoFace) {
      for (uint32_t u : faces_[f]) {
        if (u < v && n < 2) known[n++] = u;
      }
    }
    if (n == 2) {
      auto it = edge_faces_.find(EdgeKey(known[0], known[1]));
      if (it != edge_faces_.end()) {
        for (uint32_t g : it->second) {
          if (g == kNoFace || g == f) continue;
          for (uint32_t c : faces_[g]) {
            if (c != known[0] && c != known[1] && c < v) {
              IntVec3 p;
              for (int a = 0; a < 3; ++a) {
                p[a] = grid[known[0]][a] + grid[known[1]][a] - grid[c][a];
              }
              return p;
            }
          }
        }
      }
      IntVec3 p;
      for (int a = 0; a < 3; ++a) p[a] = (grid[known[0]][a] + grid[known[1]][a]) >> 1;
      return p;
    }
    if (n == 1) return grid[known[0]];
    if (v > 0) return grid[v - 1];
    return {0, 0, 0};
  }

 private:
  static constexpr uint32_t kNoFace = 0xffffffffu;
  const std::vector<Face>& faces_;
  std::vector<uint32_t> first_face_;
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> edge_faces_;
};

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_POSITIONS_H_
