// Fidelity (meshwave/fidelity.h): the remesh made denser until it reaches a
// surface PSNR against its input, the precision a fidelity needs, and the
// complete stream's PSNR against the original, each checked against an
// independent measurement with SymmetricSurfaceDistance.
#include "meshwave/fidelity.h"

#include <gtest/gtest.h>

#include <vector>

#include "meshwave/mesh_io.h"
#include "meshwave/metrics.h"
#include "meshwave/semiregular_input.h"
#include "test_data.h"

namespace meshwave {
namespace {

TriMesh Elephant() {  // irregular (remeshed), shipped in data/
  auto mesh = ReadMesh(testing::SampleMesh("elephant.off"));
  EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  return *mesh;
}

double SurfacePsnr(const TriMesh& a, const TriMesh& b, double samples_per_face) {
  SurfaceDistanceOptions options;
  options.samples_per_face = samples_per_face;
  auto d = SymmetricSurfaceDistance(a, b, options);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return d->PsnrDb(d->rms);
}

TEST(FidelityTest, PrecisionGrowsWithTheFidelityFromTheDefault) {
  EXPECT_EQ(PrecisionForFidelity(60), EncodeOptions{}.precision);
  EXPECT_EQ(PrecisionForFidelity(84), EncodeOptions{}.precision);
  EXPECT_EQ(PrecisionForFidelity(100), 17);
  EXPECT_EQ(PrecisionForFidelity(120), 20);
  EXPECT_EQ(PrecisionForFidelity(1000), 30);
}

TEST(FidelityTest, ARemeshShortOfTheFidelityIsRedoneDenserUntilItReachesIt) {
  const TriMesh input = Elephant();
  auto plain = Remesh(input);
  ASSERT_TRUE(plain.ok()) << plain.status().ToString();
  const double plain_psnr = SurfacePsnr(input, plain->mesh.Finest(), 2);
  const double asked = plain_psnr + 4;
  auto fitted = RemeshToFidelity(input, RemeshOptions{}, asked, 16);
  ASSERT_TRUE(fitted.ok()) << fitted.status().ToString();
  EXPECT_GE(fitted->attempts, 2);
  EXPECT_GE(fitted->psnr_db, asked);
  EXPECT_GT(fitted->result.finest_vertices, plain->finest_vertices);
  EXPECT_GE(fitted->result.levels, plain->levels);  // density from levels first
  // The figure it reports is the surface distance to the input, measured here again.
  EXPECT_NEAR(fitted->psnr_db, SurfacePsnr(input, fitted->result.mesh.Finest(), 2), 1e-9);
}

TEST(FidelityTest, AFidelityTheDefaultRemeshReachesTakesOneAttempt) {
  const TriMesh input = Elephant();
  auto fitted = RemeshToFidelity(input, RemeshOptions{}, 30, 16);
  ASSERT_TRUE(fitted.ok()) << fitted.status().ToString();
  EXPECT_EQ(fitted->attempts, 1);
  EXPECT_GE(fitted->psnr_db, 30);
}

TEST(FidelityTest, TheDensityLimitHolds) {
  const TriMesh input = Elephant();
  auto fitted = RemeshToFidelity(input, RemeshOptions{}, 150, 2);
  ASSERT_TRUE(fitted.ok()) << fitted.status().ToString();
  EXPECT_LT(fitted->psnr_db, 150);
  EXPECT_LE(static_cast<double>(fitted->result.finest_vertices),
            2.2 * static_cast<double>(fitted->result.input_vertices));
}

TEST(FidelityTest, ToSemiRegularPassesTheFidelityOn) {
  SemiRegularInputOptions options;
  options.fidelity_db = 1;  // any remesh has more
  auto input = ToSemiRegular(Elephant(), options);
  ASSERT_TRUE(input.ok()) << input.status().ToString();
  EXPECT_TRUE(input->remeshed);
  EXPECT_EQ(input->remesh_attempts, 1);
  EXPECT_GT(input->remesh_psnr_db, 1);
}

TEST(FidelityTest, CompleteStreamPsnrIsTheDecodedMeshsSurfaceDistanceToTheOriginal) {
  auto mesh = ReadMesh(testing::SampleMesh("holes.off"));  // semi-regular: no remesh
  ASSERT_TRUE(mesh.ok());
  auto input = ToSemiRegular(*mesh);
  ASSERT_TRUE(input.ok());
  std::vector<double> reached;
  for (int precision : {10, 16}) {
    EncodeOptions options;
    options.precision = precision;
    auto stream = EncodeMesh(input->mesh, options);
    ASSERT_TRUE(stream.ok());
    auto psnr = CompleteStreamPsnr(*mesh, *stream);
    ASSERT_TRUE(psnr.ok()) << psnr.status().ToString();
    // Independently: the stream's own mesh (what a full decode gives within
    // the quantisation error) is near the original, more so at 16 bits.
    EXPECT_GT(*psnr, precision == 10 ? 60 : 95) << precision;
    EXPECT_LT(*psnr, precision == 10 ? 90 : 130) << precision;
    reached.push_back(*psnr);
  }
  // Six more bits: about 6 dB each (the quantisation error is all there is).
  EXPECT_GT(reached[1] - reached[0], 30);
}

}  // namespace
}  // namespace meshwave
