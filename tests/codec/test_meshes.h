// Small meshes built in code for unit tests: closed, open, genus 1, and a
// helper that shuffles vertex and face order.
#ifndef MESHWAVE_TESTS_CODEC_TEST_MESHES_H_
#define MESHWAVE_TESTS_CODEC_TEST_MESHES_H_

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "meshwave/mesh.h"

namespace meshwave::testing {

inline TriMesh Octahedron() {
  TriMesh m;
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

inline TriMesh Icosahedron() {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriMesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                 {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                 {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

// An open, irregular patch: a hexagonal fan around a valence-5 hub plus a
// ring, so it has boundary vertices of several valences.
inline TriMesh OpenPatch() {
  TriMesh m;
  m.positions.push_back({0, 0, 0.2});
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * M_PI * i / 5;
    m.positions.push_back({std::cos(a), std::sin(a), 0.1 * i});
  }
  for (int i = 0; i < 6; ++i) {
    const double a = 2 * M_PI * (i + 0.5) / 7;
    m.positions.push_back({2 * std::cos(a), 2 * std::sin(a), 0.05 * i * i});
  }
  for (uint32_t i = 0; i < 5; ++i) m.faces.push_back({0, 1 + i, 1 + (i + 1) % 5});
  // Stitch the inner pentagon (1..5) to part of the outer arc (6..11).
  m.faces.push_back({1, 6, 2});
  m.faces.push_back({2, 6, 7});
  m.faces.push_back({2, 7, 3});
  m.faces.push_back({3, 7, 8});
  m.faces.push_back({3, 8, 9});
  m.faces.push_back({3, 9, 4});
  m.faces.push_back({4, 9, 10});
  m.faces.push_back({4, 10, 5});
  m.faces.push_back({5, 10, 11});
  return m;
}

// A torus of n x m quads, each split along the same diagonal: every vertex
// has valence 6, so there is no extraordinary vertex at all.
inline TriMesh Torus(int n, int m, double big = 2.0, double small = 0.7) {
  TriMesh t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.positions.push_back({(big + small * std::cos(v)) * std::cos(u),
                             (big + small * std::cos(v)) * std::sin(u),
                             small * std::sin(v)});
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<uint32_t>(((i + n) % n) * m + (j + m) % m);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      t.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return t;
}

// The same mesh with vertices and faces in a random order, and each face's
// corners rotated at random (orientation kept).
inline TriMesh Shuffled(const TriMesh& in, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> perm(in.positions.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  TriMesh out;
  out.positions.resize(in.positions.size());
  for (size_t v = 0; v < perm.size(); ++v) out.positions[perm[v]] = in.positions[v];
  out.faces = in.faces;
  for (Face& f : out.faces) {
    for (uint32_t& v : f) v = perm[v];
    std::rotate(f.begin(), f.begin() + rng() % 3, f.end());
  }
  std::shuffle(out.faces.begin(), out.faces.end(), rng);
  return out;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_TEST_MESHES_H_
