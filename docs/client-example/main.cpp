// fetch_example URL BYTES OUT.ply: fetches a mesh from a meshwave-server at
// a byte budget, printing each refinement, and writes the result.
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "meshwave/client/blocking_session.h"
#include "meshwave/mesh.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(
        stderr,
        "usage: fetch_example http://host:port/v1/meshes/ID BYTES OUT.ply\n");
    return 2;
  }
  auto url = meshwave::client::ParseMeshUrl(argv[1]);
  if (!url.ok()) {
    std::fprintf(stderr, "%s\n", url.status().ToString().c_str());
    return 1;
  }
  meshwave::client::BlockingSession session(*url, {}, {});
  const auto budget =
      meshwave::client::Budget::Bytes(std::strtoull(argv[2], nullptr, 10));
  meshwave::Status s =
      session.Fetch(budget, [](const meshwave::client::Progress& p,
                               const meshwave::ProgressiveDecoder&) {
        std::printf(
            "%zu packets, %llu bytes, level %d, estimated PSNR %.2f dB\n",
            p.packets, static_cast<unsigned long long>(p.bytes), p.level,
            p.estimated_psnr_db);
      });
  if (s.ok()) {
    // meshwave::client links the decoder library only: PLY bytes from it,
    // written here (WriteMesh, with its atomic rename, is meshwave::codec's).
    std::ofstream out(argv[3], std::ios::binary);
    out << meshwave::SerializePly(session.session().decoder()->Mesh());
    if (!out) s = meshwave::IoError(std::string(argv[3]) + ": cannot write");
  }
  if (!s.ok()) {
    std::fprintf(stderr, "%s\n", s.ToString().c_str());
    return 1;
  }
  return 0;
}
