// Vertex colours onto a remesh: each vertex of the semi-regular mesh takes
// the colour of the nearest point of the original surface, interpolated
// from that face's corner colours. The remesh's vertices lie on (or within
// its fitting error of) the original surface, so the nearest point is the
// point the vertex stands for.
#ifndef MESHWAVE_PIPELINE_COLOR_TRANSFER_H_
#define MESHWAVE_PIPELINE_COLOR_TRANSFER_H_

#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

// Barycentric coordinates (w0, w1, w2) of `p` with respect to triangle
// (a, b, c), each in [0, 1], summing to 1, of the point of the triangle
// nearest to p. A degenerate triangle (collinear or coincident corners)
// weighs the ends of its longest edge, the third corner 0; coincident
// corners get 1/3 each.
Vec3 ClosestBarycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// For each of `targets`, the linear RGB (alpha dropped) of the nearest
// point of the surface (positions, faces), interpolated from `color`'s
// corner values of that face. Colours are the asset's: linear, so the
// interpolation is physically meaningful (a PLY's sRGB bytes were decoded
// by its reader). Among equally near faces, for example at a vertex where
// the corner colours of its faces differ, any one may give the colour.
// kInvalidArgument when `color` is empty, does not have a corner triple
// per face, indexes past its values or past `positions`, or the surface
// has no face. `threads` as ResolveThreads takes them; the result does not
// depend on it.
Result<std::vector<Vec3>> TransferCornerColors(const std::vector<Vec3>& positions,
                                               const std::vector<Face>& faces,
                                               const CornerAttribute<Eigen::Vector4f>& color,
                                               const std::vector<Vec3>& targets,
                                               int threads = 1);

}  // namespace meshwave

#endif  // MESHWAVE_PIPELINE_COLOR_TRANSFER_H_
