// The encoder settings a catalog row records: canonical text that reads
// back to the same choices, and clear refusals of anything else.
#include "encode_settings.h"

#include <gtest/gtest.h>

namespace meshwave::server {
namespace {

TEST(EncodeSettingsTest, DefaultsHaveOneCanonicalText) {
  EXPECT_EQ(FormatEncodeSettings(EncodeChoices{}),
            "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=4096 split=48");
  EncodeChoices threaded;
  threaded.threads = 7;  // does not change the container
  EXPECT_EQ(FormatEncodeSettings(threaded), FormatEncodeSettings(EncodeChoices{}));
}

TEST(EncodeSettingsTest, ReadsBackWhatItWrote) {
  EncodeChoices c;
  c.fidelity_db = 91.25;
  c.max_vertex_ratio = 2.5;
  c.force_remesh = true;
  c.precinct_coefficients = 0;
  c.split_bytes_per_precinct = 7;
  const std::string text = FormatEncodeSettings(c);
  auto back = ParseEncodeSettings(text);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->fidelity_db, 91.25);
  EXPECT_EQ(back->max_vertex_ratio, 2.5);
  EXPECT_TRUE(back->force_remesh);
  EXPECT_EQ(back->precinct_coefficients, 0u);
  EXPECT_EQ(back->split_bytes_per_precinct, 7u);
  EXPECT_EQ(FormatEncodeSettings(*back), text);
  // Any order of the fields.
  auto shuffled = ParseEncodeSettings("split=48 precinct=4096 remesh=auto max_vertex_ratio=4 fidelity=84");
  ASSERT_TRUE(shuffled.ok());
  EXPECT_EQ(FormatEncodeSettings(*shuffled), FormatEncodeSettings(EncodeChoices{}));
}

TEST(EncodeSettingsTest, RefusesWhatItDidNotWrite) {
  const std::string good = "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=4096 split=48";
  struct Case {
    std::string text;
    std::string says;
  } cases[] = {
      {"", "fidelity missing"},
      {good + " colour=1", "unknown key 'colour'"},
      {good + " split=3", "split given twice"},
      {"fidelity=84 max_vertex_ratio=4 remesh=maybe precinct=4096 split=48", "remesh=maybe"},
      {"fidelity=x max_vertex_ratio=4 remesh=auto precinct=4096 split=48", "fidelity=x"},
      {"fidelity=nan max_vertex_ratio=4 remesh=auto precinct=4096 split=48", "fidelity=nan"},
      {"fidelity=84 max_vertex_ratio=0.5 remesh=auto precinct=4096 split=48", "max_vertex_ratio"},
      {"fidelity=84 max_vertex_ratio=4 remesh=auto precinct=-1 split=48", "precinct=-1"},
      {"fidelity=84  max_vertex_ratio=4 remesh=auto precinct=4096 split=48", "not key=value"},
  };
  for (const Case& c : cases) {
    auto r = ParseEncodeSettings(c.text);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(c.says), std::string::npos)
        << c.text << ": " << r.status().message();
  }
}

}  // namespace
}  // namespace meshwave::server
