// Ingest on several threads (remeshing, then encoding) gives the very
// bytes of the single-threaded run: the container of a remeshed mesh and of
// a semi-regular one, for every coder, at 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/mesh_io.h"
#include "meshwave/remesh.h"
#include "meshwave/semiregular_input.h"
#include "test_data.h"

namespace meshwave {
namespace {

// What `meshwave encode` and the server's ingest do with a mesh, on
// `threads` threads: the container's bytes.
std::string Ingest(const TriMesh& mesh, int threads, EncodeOptions options = {}) {
  SemiRegularInputOptions input_options;
  input_options.threads = threads;
  // Under the sanitizers one remesh instead of the default fidelity's two or
  // three of the same (parallel) remesher: 80 s -> 15 s under ASan.
  if (testing::kUnderSanitizer) input_options.fidelity_db = 0;
  auto input = ToSemiRegular(mesh, input_options);
  EXPECT_TRUE(input.ok()) << input.status().ToString();
  if (!input.ok()) return {};
  options.threads = threads;
  auto stream = EncodeMesh(input->mesh, options);
  EXPECT_TRUE(stream.ok()) << stream.status().ToString();
  if (!stream.ok()) return {};
  return SerializeFullContainer(*stream);
}

void ExpectSameBytesAtAnyThreadCount(const TriMesh& mesh, const EncodeOptions& options = {}) {
  const std::string one = Ingest(mesh, 1, options);
  ASSERT_FALSE(one.empty());
  for (int threads : {2, 3}) {
    const std::string many = Ingest(mesh, threads, options);
    EXPECT_EQ(many.size(), one.size()) << threads << " threads";
    EXPECT_TRUE(many == one) << threads << " threads: the container differs";
  }
}

TriMesh Read(const std::filesystem::path& path) {
  auto mesh = ReadMesh(path);
  EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  return mesh.ok() ? *mesh : TriMesh{};
}

TEST(PipelineThreadsTest, ARemeshedMeshGivesTheSameContainerOnAnyThreadCount) {
  ExpectSameBytesAtAnyThreadCount(Read(testing::SampleMesh("elephant.off")));
}

// Large enough that every parallel loop of the remesher and the encoder
// splits into chunks (35 k vertices, 70 k faces).
TEST(PipelineThreadsTest, ALargerRemeshedMeshGivesTheSameContainerOnAnyThreadCount) {
  if (testing::kUnderSanitizer) GTEST_SKIP() << "elephant.off covers this under sanitizers";
  MESHWAVE_REQUIRE_SHARED_MESH("bunny_stanford_zipper.ply");
  ExpectSameBytesAtAnyThreadCount(Read(testing::SharedMesh("bunny_stanford_zipper.ply")));
}

TEST(PipelineThreadsTest, EveryCoderGivesTheSameStreamOnAnyThreadCount) {
  const TriMesh holes = Read(testing::SampleMesh("holes.off"));  // semi-regular
  EncodeOptions sim;
  sim.coder = CoderKind::kSim;
  EncodeOptions deadzones;
  deadzones.auto_deadzone = true;
  EncodeOptions sawt;
  sawt.transform.predictor = Predictor::kSawt;
  sawt.transform.update = UpdateWeights::kNone;
  for (const EncodeOptions& options : {EncodeOptions{}, sim, deadzones, sawt}) {
    ExpectSameBytesAtAnyThreadCount(holes, options);
  }
}

}  // namespace
}  // namespace meshwave
