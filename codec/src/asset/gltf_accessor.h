// Reading glTF accessors with every bound checked: tinygltf parses the JSON
// but trusts the numbers in it (offsets, strides, counts, sparse indices),
// so the reads go through here. An accessor's elements must lie inside its
// bufferView and the view inside its buffer; sparse indices must be below
// the accessor's count; counts are capped before anything is allocated.
#ifndef MESHWAVE_ASSET_GLTF_ACCESSOR_H_
#define MESHWAVE_ASSET_GLTF_ACCESSOR_H_

#include <cstdint>
#include <string>
#include <vector>

#include "asset/tiny_gltf_config.h"
#include "meshwave/status.h"

namespace meshwave {

// What a caller accepts of an accessor. Masks have bit ComponentBit(c) set
// for each accepted glTF component type c (5120 BYTE ... 5126 FLOAT).
struct AccessorSpec {
  const char* what;              // for messages: "POSITION", "indices"
  uint32_t type_mask = 0;        // bit (1 << components) per accepted type
  uint32_t plain_mask = 0;       // component types read as they are
  uint32_t normalized_mask = 0;  // component types accepted normalised
  uint64_t max_count = 0;        // elements at most
};

inline constexpr uint32_t ComponentBit(int component_type) {
  return 1u << (component_type - 5120);
}
inline constexpr uint32_t TypeBit(int components) { return 1u << components; }

// The elements of accessor `index` as doubles, `components` per element
// (set from the accessor's type), normalised integers mapped to [0, 1] or
// [-1, 1] as glTF 2.0 section 3.11 says. `context` ("mesh 2 \"Car\"
// primitive 0") leads every message.
struct AccessorValues {
  int components = 0;
  size_t count = 0;
  std::vector<double> values;  // count * components
};
Result<AccessorValues> ReadAccessor(const tinygltf::Model& model, int index,
                                    const AccessorSpec& spec,
                                    const std::string& context);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_ACCESSOR_H_
