// SAWT in the stream: the header field a decoder reads back into the
// encoder's regions and filters, through the container, refusals of a
// corrupt field, and the quality of a complete decode.
#include <gtest/gtest.h>

#include <random>

#include "codec/stream/stream_test_util.h"
#include "meshwave/container.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/subdivision.h"
#include "stream/base_mesh_decoder.h"
#include "stream/sawt_field_decoder.h"
#include "stream/stream_format.h"
#include "stream/stream_format_writer.h"
#include "stream/stream_preparation.h"
#include "test_data.h"
#include "wavelet/sawt_plan.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {
namespace {

// The shipped copy of the shared holes_patch_sr2 mesh (data/README.md):
// semi-regular, 2 levels, 7 boundary loops.
SemiRegularMesh HolesPatch() {
  auto read = ReadMesh(testing::SampleMesh("holes.off"));
  EXPECT_TRUE(read.ok()) << read.status().ToString();
  auto detected = DetectSemiRegular(*read);
  EXPECT_TRUE(detected.ok()) << detected.status().ToString();
  return detected->mesh;
}

EncodeOptions SawtOptions(UpdateWeights update, uint32_t alpha) {
  EncodeOptions o = testing::EqualStepOptions();
  o.transform.predictor = Predictor::kSawt;
  o.transform.update = update;
  o.sawt_alpha = alpha;
  return o;
}

// What a decoder derives from the header alone.
std::shared_ptr<const SawtPlan> DecoderPlan(const StreamHeader& header) {
  auto base = DecodeBaseMesh(header.base, 1u << 20);
  EXPECT_TRUE(base.ok()) << base.status().ToString();
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(base->positions.size()),
                                       base->faces, static_cast<int>(header.transform.levels));
  EXPECT_TRUE(h.ok());
  auto plan = DecodeSawtChoices(*header.transform.sawt, **h, base->grid);
  EXPECT_TRUE(plan.ok()) << plan.status().ToString();
  return plan.ok() ? *plan : nullptr;
}

TEST(SawtStreamTest, DecoderFindsTheEncodersRegionsAndFilters) {
  struct Case {
    SemiRegularMesh mesh;
    UpdateWeights update;
    uint32_t alpha;
  };
  const std::vector<Case> cases = {{HolesPatch(), UpdateWeights::kNone, 400},
                                   {HolesPatch(), UpdateWeights::kConstant, 200},
                                   {testing::BumpySphere(3), UpdateWeights::kNone, 60}};
  for (const Case& c : cases) {
    auto prepared = PrepareStream(c.mesh, SawtOptions(c.update, c.alpha));
    ASSERT_TRUE(prepared.ok()) << prepared.status().ToString();
    const SawtPlan& encoder = *prepared->transform.sawt;
    ASSERT_GT(encoder.regions.count, 3u);
    auto header = ToStreamHeader(prepared->header);  // the encoder's own proto
    ASSERT_TRUE(header.ok());
    const auto decoder = DecoderPlan(*header);
    ASSERT_NE(decoder, nullptr);
    EXPECT_EQ(decoder->regions.count, encoder.regions.count);
    EXPECT_EQ(decoder->filters, encoder.filters);
    const auto& h = *prepared->mesh.hierarchy;
    for (int j = 0; j < h.levels(); ++j) {
      EXPECT_EQ(SawtOddVertexRegions(h, j, decoder->regions.face_region),
                SawtOddVertexRegions(h, j, encoder.regions.face_region))
          << "level " << j;
    }
  }
}

const EncodedStream& HolesStream() {
  static const EncodedStream s = [] {
    auto r = EncodeMesh(HolesPatch(), SawtOptions(UpdateWeights::kNone, 400));
    EXPECT_TRUE(r.ok()) << r.status().ToString();
    return *std::move(r);
  }();
  return s;
}

std::vector<Vec3> DecodeEverything(const StreamHeader& header,
                                   const std::vector<std::string>& payloads,
                                   const std::vector<uint32_t>& ids) {
  auto d = ProgressiveDecoder::Create(header);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  if (!d.ok()) return {};
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_TRUE((*d)->AddPacket(ids[i], payloads[i]).ok());
  }
  return (*d)->Positions();
}

TEST(SawtStreamTest, FieldSurvivesTheContainerAndDecodesNearLossless) {
  const EncodedStream& s = HolesStream();
  ASSERT_EQ(s.header.transform.predictor, StreamPredictor::kSawt);
  ASSERT_TRUE(s.header.transform.sawt);
  ASSERT_GT(s.header.transform.sawt->coded.size(), 0u);
  const std::string bytes = SerializeFullContainer(s);  // the payloads view into it
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  ASSERT_TRUE(parsed->header.transform.sawt);
  EXPECT_EQ(parsed->header.transform.sawt->coded, s.header.transform.sawt->coded);
  EXPECT_EQ(parsed->header.transform.sawt->crc32c, s.header.transform.sawt->crc32c);
  EXPECT_EQ(parsed->header.transform.sawt->region_count, s.header.transform.sawt->region_count);
  EXPECT_EQ(parsed->header.transform.sawt->alpha, s.header.transform.sawt->alpha);
  const std::vector<Vec3> decoded = DecodeEverything(
      parsed->header, std::vector<std::string>(parsed->payloads.begin(), parsed->payloads.end()),
      parsed->ids);
  const double diag = BoundingBox(s.mesh.positions).Diagonal();
  const double sawt_psnr = testing::Psnr(decoded, s.mesh.positions, diag);
  // The default transform's complete stream, for the same mesh.
  auto reference = EncodeMesh(HolesPatch(), testing::EqualStepOptions());
  ASSERT_TRUE(reference.ok());
  std::vector<uint32_t> all(reference->packets.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  const double default_psnr = testing::Psnr(
      DecodeEverything(reference->header, reference->packets, all), reference->mesh.positions,
      diag);
  EXPECT_GT(sawt_psnr, 90.0);
  EXPECT_GT(sawt_psnr, default_psnr - 1.0) << "default " << default_psnr;
}

Status CreateWith(const StreamHeader& header) {
  return ProgressiveDecoder::Create(header).status();
}

TEST(SawtStreamTest, CorruptFieldIsRefusedWithAClearError) {
  const StreamHeader& good = HolesStream().header;
  ASSERT_TRUE(CreateWith(good).ok());
  auto expect_refused = [](const StreamHeader& h, const std::string& what) {
    const Status s = CreateWith(h);
    EXPECT_FALSE(s.ok()) << what;
    EXPECT_NE(s.message().find("SAWT"), std::string::npos) << what << ": " << s.ToString();
  };
  {
    StreamHeader h = good;
    h.transform.sawt->coded.resize(good.transform.sawt->coded.size() / 3);
    expect_refused(h, "truncated codeword");
  }
  {
    StreamHeader h = good;
    h.transform.sawt->region_count = good.transform.sawt->region_count + 1;
    expect_refused(h, "region count");
  }
  {
    StreamHeader h = good;
    h.transform.sawt.reset();
    expect_refused(h, "missing field");
  }
  {
    StreamHeader h = good;
    h.transform.predictor = StreamPredictor::kButterfly;
    expect_refused(h, "field with another predictor");
  }
  // Any damage to the codeword, cut or flipped bytes, is caught by its CRC.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    StreamHeader h = good;
    std::string& coded = h.transform.sawt->coded;
    coded[rng() % coded.size()] ^= static_cast<char>(1 + rng() % 255);
    if (trial % 2) coded.resize(rng() % (coded.size() + 1));
    expect_refused(h, "damage " + std::to_string(trial));
  }
}

}  // namespace
}  // namespace meshwave
