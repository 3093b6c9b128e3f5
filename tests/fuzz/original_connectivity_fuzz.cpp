// Fuzz target: the original layer's connectivity decoder
// (original/original_connectivity.h) on arbitrary bytes. The first four
// bytes are the counts a header would announce (vertices and faces, 16
// bits each, little-endian: small, so that an execution is cheap); the
// rest is the payload. A decode that succeeds must be a valid traversal,
// and re-encoding its faces must decode to the same faces.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_require_testonly.h"
#include "original/original_connectivity.h"
#include "original/original_connectivity_code.h"

using namespace meshwave;
using namespace meshwave::original;

namespace {

std::vector<Face> Canonical(std::vector<Face> faces) {
  for (Face& f : faces) f = RotateToSmallest(f);
  std::sort(faces.begin(), faces.end());
  return faces;
}

void RequireValid(const Traversal& t, uint32_t vertex_count, uint64_t face_count) {
  fuzz::Require(t.faces.size() == face_count, "as many faces as announced");
  fuzz::Require(t.order.size() == vertex_count, "every vertex in the order");
  fuzz::Require(t.predictions.size() == vertex_count, "a prediction per vertex");
  std::vector<uint32_t> position(vertex_count, kNoVertex);
  for (size_t i = 0; i < t.order.size(); ++i) {
    fuzz::Require(t.order[i] < vertex_count && position[t.order[i]] == kNoVertex,
                  "the order is a permutation");
    position[t.order[i]] = static_cast<uint32_t>(i);
  }
  for (size_t i = 0; i < t.predictions.size(); ++i) {
    for (uint32_t v : {t.predictions[i].a, t.predictions[i].b, t.predictions[i].c}) {
      fuzz::Require(v == kNoVertex || (v < vertex_count && position[v] < i),
                    "predictions name earlier vertices");
    }
  }
  for (const Face& f : t.faces) {
    for (uint32_t v : f) fuzz::Require(v < vertex_count, "face ids in range");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 4) return 0;
  const uint32_t vertex_count = data[0] | uint32_t{data[1]} << 8;
  const uint64_t face_count = data[2] | uint32_t{data[3]} << 8;
  const std::string_view payload(reinterpret_cast<const char*>(data) + 4, size - 4);
  auto decoded = DecodeConnectivity(payload, vertex_count, face_count);
  if (!decoded.ok()) {
    fuzz::Require(decoded.status().code() == StatusCode::kParseError, "damage is a parse error");
    return 0;
  }
  RequireValid(*decoded, vertex_count, face_count);
  Traversal sent;
  auto again = EncodeConnectivity(vertex_count, decoded->faces, &sent);
  fuzz::Require(again.ok(), "decoded faces re-encode");
  auto round = DecodeConnectivity(*again, vertex_count, face_count);
  fuzz::Require(round.ok(), "the re-encoding decodes");
  fuzz::Require(round->faces == sent.faces && round->order == sent.order,
                "encoder and decoder agree");
  fuzz::Require(Canonical(round->faces) == Canonical(decoded->faces), "the same faces come back");
  return 0;
}
