// A hash of three 32-bit values for unordered containers keyed by triples
// (faces, quantised points): splitmix64-style multiply and xor-shift rounds.
#ifndef MESHWAVE_CORE_HASH_MIX_H_
#define MESHWAVE_CORE_HASH_MIX_H_

#include <cstddef>
#include <cstdint>

namespace meshwave {

inline size_t HashTriple(uint32_t a, uint32_t b, uint32_t c) {
  uint64_t h = a * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) + b * 0xBF58476D1CE4E5B9ull;
  h ^= (h >> 31) + c * 0x94D049BB133111EBull;
  return static_cast<size_t>(h ^ (h >> 32));
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_HASH_MIX_H_
