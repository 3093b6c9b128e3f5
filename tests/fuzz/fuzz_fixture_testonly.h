// A small real container (FixtureContainerPath(): the octahedron subdivided
// three times, or for the decoder targets the tetrahedron subdivided twice;
// tests/fuzz/CMakeLists.txt) loaded once per fuzzing process: the fixed
// header and payloads the packet and decoder-order targets mutate around.
// The octahedron is made (in tests/fuzz/) with
//   meshwave subdivide data/octahedron.off oct3.ply --levels 3 --scheme midpoint
//   meshwave encode oct3.ply data/octahedron_sr3.mwv
// the tetrahedron as make_seeds.py says; both are remade whenever the format
// changes (then run make_seeds.py).
#ifndef MESHWAVE_TESTS_FUZZ_FUZZ_FIXTURE_TESTONLY_H_
#define MESHWAVE_TESTS_FUZZ_FUZZ_FIXTURE_TESTONLY_H_

#include <google/protobuf/stubs/logging.h>

#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_require_testonly.h"
#include "meshwave/container.h"
#include "meshwave/progressive_decoder.h"

namespace meshwave::fuzz {

// The container's path: one small file generated per target
// (meshwave_add_fuzz), so no other object names a path of this clone.
const char* FixtureContainerPath();

struct Fixture {
  std::string bytes;                  // the whole container
  StreamHeader header;                // present cleared
  std::vector<std::string> payloads;  // by packet id
  std::vector<Vec3> full;             // positions with every packet decoded
};

// Protobuf logs every string field that is not UTF-8: noise at fuzzing
// speed, and the parse fails cleanly anyway.
inline const bool kQuietProtobuf = [] {
  google::protobuf::SetLogHandler(nullptr);
  return true;
}();

// Aborts (a harness error, not a finding) when the fixture is unusable.
inline const Fixture& GetFixture() {
  static const Fixture fixture = [] {
    Fixture f;
    std::ifstream in(FixtureContainerPath(), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    f.bytes = ss.str();
    auto parsed = ParseContainer(f.bytes);
    if (!parsed.ok()) {
      std::fprintf(stderr, "fuzz fixture %s: %s\n", FixtureContainerPath(),
                   parsed.status().message().c_str());
      std::abort();
    }
    f.header = parsed->header;
    f.header.present.clear();
    f.payloads.resize(f.header.packets.length.size());
    for (size_t i = 0; i < parsed->ids.size(); ++i) {
      f.payloads[parsed->ids[i]] = std::string(parsed->payloads[i]);
    }
    auto dec = ProgressiveDecoder::Create(f.header);
    if (!dec.ok()) std::abort();
    for (uint32_t id = 0; id < f.payloads.size(); ++id) {
      if (!(*dec)->AddPacket(id, f.payloads[id]).ok()) std::abort();
    }
    f.full = (*dec)->Positions();
    return f;
  }();
  return fixture;
}


}  // namespace meshwave::fuzz

#endif  // MESHWAVE_TESTS_FUZZ_FUZZ_FIXTURE_TESTONLY_H_
