// The /metrics text: well-formed Prometheus exposition lines, and a
// histogram whose +Inf bucket, _sum and _count agree with what was recorded.
#include "metrics.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

namespace meshwave::server {
namespace {

// name{labels} -> value of every sample line; fails on a line that is not
// a comment nor "name[{labels}] value".
std::map<std::string, double> Samples(const std::string& text) {
  std::map<std::string, double> out;
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("# HELP ") || line.starts_with("# TYPE ")) continue;
    const size_t space = line.rfind(' ');
    EXPECT_NE(space, std::string::npos) << line;
    if (space == std::string::npos) continue;
    const std::string name = line.substr(0, space);
    EXPECT_TRUE(name.starts_with("meshwave_")) << line;
    EXPECT_EQ(name.find('#'), std::string::npos) << line;
    size_t used = 0;
    const double value = std::stod(line.substr(space + 1), &used);
    EXPECT_EQ(used, line.size() - space - 1) << line;
    EXPECT_TRUE(out.emplace(name, value).second) << "repeated: " << line;
  }
  return out;
}

TEST(MetricsTest, HistogramLinesAreWellFormed) {
  Metrics m;
  m.RecordRequest(200, 100, 0.0002);
  m.RecordRequest(200, 100, 0.003);
  m.RecordRequest(404, 50, 2.0);
  m.RecordRequest(200, 100, 10.0);  // beyond the last finite bucket
  const auto s = Samples(m.Render(3, 1));
  const std::string h = "meshwave_http_request_duration_seconds";
  ASSERT_TRUE(s.count(h + "_bucket{le=\"+Inf\"}"));
  ASSERT_TRUE(s.count(h + "_sum"));
  ASSERT_TRUE(s.count(h + "_count"));
  EXPECT_EQ(s.at(h + "_bucket{le=\"+Inf\"}"), 4);
  EXPECT_EQ(s.at(h + "_count"), 4);
  EXPECT_NEAR(s.at(h + "_sum"), 12.0032, 1e-5);
  EXPECT_EQ(s.at(h + "_bucket{le=\"0.0005\"}"), 1);
  EXPECT_EQ(s.at(h + "_bucket{le=\"0.005\"}"), 2);
  EXPECT_EQ(s.at(h + "_bucket{le=\"5\"}"), 3);
  // Cumulative: no bucket holds more than a wider one.
  double previous = 0;
  for (const char* le : {"0.0005", "0.001", "0.0025", "0.005", "0.01", "0.025", "0.05", "0.1",
                         "0.25", "0.5", "1", "5", "+Inf"}) {
    const double v = s.at(h + "_bucket{le=\"" + le + "\"}");
    EXPECT_GE(v, previous) << le;
    previous = v;
  }
  EXPECT_EQ(s.at("meshwave_http_requests_total{code=\"200\"}"), 3);
  EXPECT_EQ(s.at("meshwave_http_requests_total{code=\"404\"}"), 1);
  EXPECT_EQ(s.at("meshwave_http_response_bytes_total"), 350);
  EXPECT_EQ(s.at("meshwave_catalog_meshes"), 3);
  EXPECT_EQ(s.at("meshwave_open_containers"), 1);
}

TEST(MetricsTest, LargeCountsStayOnTheirOwnLines) {
  Metrics m;
  for (int i = 0; i < 1000; ++i) m.RecordRequest(200, uint64_t{1} << 40, 4.5);
  const auto s = Samples(m.Render(uint64_t{1} << 50, 123456789));
  EXPECT_EQ(s.at("meshwave_http_request_duration_seconds_count"), 1000);
  EXPECT_NEAR(s.at("meshwave_http_request_duration_seconds_sum"), 4500, 1e-3);
  EXPECT_EQ(s.at("meshwave_catalog_meshes"), static_cast<double>(uint64_t{1} << 50));
}

TEST(MetricsTest, EmptyRenderIsWellFormed) {
  Metrics m;
  const auto s = Samples(m.Render(0, 0));
  EXPECT_EQ(s.at("meshwave_http_request_duration_seconds_count"), 0);
  EXPECT_EQ(s.at("meshwave_http_connections"), 0);
}

}  // namespace
}  // namespace meshwave::server
