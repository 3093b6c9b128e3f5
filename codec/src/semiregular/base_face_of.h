// Which base face a coefficient belongs to: the rule that groups the
// coefficients by base face for the SAWT regions (Denis et al. 2010a) and
// for the precincts (stream/precinct_partition.h).
#ifndef MESHWAVE_SEMIREGULAR_BASE_FACE_OF_H_
#define MESHWAVE_SEMIREGULAR_BASE_FACE_OF_H_

#include <cstdint>
#include <vector>

#include "meshwave/semiregular.h"

namespace meshwave {

// The base face that coefficient k of d^j (the midpoint of edge k of M^j)
// lies in: face f of M^j descends from base face f >> 2j, and a midpoint on
// a base edge goes to the adjacent base face of lower index.
inline uint32_t BaseFaceOf(const SemiRegularHierarchy& h, int j, uint32_t k) {
  const auto& ef = h.edge_faces(j)[k];
  const uint32_t a = ef[0] >> (2 * j);
  if (ef[1] == SemiRegularHierarchy::kNone) return a;
  const uint32_t b = ef[1] >> (2 * j);
  return a < b ? a : b;
}

// How many coefficients of d^j each base face holds, added to `held`
// (one entry per base face).
template <class Count>
void AddCoefficientsPerBaseFace(const SemiRegularHierarchy& h, int j, std::vector<Count>& held) {
  const uint32_t n = static_cast<uint32_t>(h.subband_size(j));
  for (uint32_t k = 0; k < n; ++k) ++held[BaseFaceOf(h, j, k)];
}

}  // namespace meshwave

#endif  // MESHWAVE_SEMIREGULAR_BASE_FACE_OF_H_
