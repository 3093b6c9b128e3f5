// A point from which a vertex's whole one-ring is seen the right way round:
// where fold repair puts a vertex whose ring centroid would leave it folded.
#ifndef MESHWAVE_REMESH_RING_KERNEL_H_
#define MESHWAVE_REMESH_RING_KERNEL_H_

#include <cstddef>
#include <cstdint>
#include <span>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

// Rings of more vertices than this use their first kMaxKernelRing only
// (valences above it occur only in odd bases).
inline constexpr size_t kMaxKernelRing = 64;

// Height the kernel point keeps over each ring edge, as a fraction of that
// edge: about a 6° corner at worst.
inline constexpr double kKernelMargin = 0.1;

// A point of the plane through `start` with unit normal n from which every
// triangle to two consecutive vertices of `ring` (closed, counter-clockwise
// seen from n; positions[ring[i]] projected into the plane) is positively
// oriented with kKernelMargin of height to spare: a point of the kernel of
// the star-shaped ring polygon, found by cyclic projection onto the
// half-planes of its edges, starting at `start` (projections onto convex
// sets: L. M. Bregman, "The method of successive projection for finding a
// common point of convex sets", 1965; L. G. Gubin, B. T. Polyak, E. V.
// Raik, "The method of projections for finding the common point of convex
// sets", 1967). The ring centroid, the relaxation target, stays in a
// fold when the ring polygon is not convex (a reflex corner); the kernel
// does not. When the kernel is empty the iteration stops (after a fixed
// number of sweeps) near it.
Vec3 RingKernelPoint(std::span<const Vec3> positions, const Vec3& start,
                     const Vec3& n, std::span<const uint32_t> ring);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_RING_KERNEL_H_
