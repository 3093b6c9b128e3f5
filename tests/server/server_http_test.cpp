// The meshwave-server binary end to end: ingest the sample meshes, start it
// on a free port, and check every endpoint that reads the catalog with a
// Beast client, including the refusals, then stop it with SIGTERM (exit
// code 0). The requests that change the catalog: server_catalog_http_test.cpp.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "catalog.h"
#include "catalog_api.pb.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "meshwave/container.h"
#include "meshwave/metrics.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "server_http_fixture_testonly.h"
#include "server_process_testonly.h"
#include "stream.pb.h"
#include "sha256.h"
#include "stream/stream_format.h"
#include "test_data.h"

namespace meshwave::testing {
namespace {

using server::Sha256Hex;

// Decodes a container; the positions of the finest level.
std::vector<Vec3> Decode(std::string_view bytes, double* estimated_psnr = nullptr) {
  auto parsed = ParseContainer(bytes);
  EXPECT_TRUE(parsed.ok()) << parsed.status().ToString();
  if (!parsed.ok()) return {};
  auto decoder = ProgressiveDecoder::Create(parsed->header);
  EXPECT_TRUE(decoder.ok());
  if (!decoder.ok()) return {};
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    EXPECT_TRUE((*decoder)->AddPacket(parsed->ids[i], parsed->payloads[i]).ok());
  }
  if (estimated_psnr) *estimated_psnr = (*decoder)->EstimatedPsnr();
  return (*decoder)->Positions();
}

double Diagonal(const StreamHeader& h) {
  double d = 0;
  for (size_t a = 0; a < 3; ++a) d += std::pow(h.bbox_max[a] - h.bbox_min[a], 2);
  return std::sqrt(d);
}

double Psnr(const std::vector<Vec3>& reference, const std::vector<Vec3>& test, double peak) {
  auto e = VertexError(reference, test, peak);
  EXPECT_TRUE(e.ok());
  return e.ok() ? e->psnr_db : -1;
}

TEST_F(ServerHttpTest, ListsCatalogAsJsonWithPaging) {
  const HttpReply all = HttpGet(port_, "/v1/meshes");
  EXPECT_EQ(all.Header("content-type"), "application/json");
  const proto::MeshList list = ParseList(all.body);
  EXPECT_EQ(list.total(), 4u);
  ASSERT_EQ(list.meshes_size(), 4);
  for (const auto& m : list.meshes()) {
    EXPECT_GT(m.vertices(), 0u);
    EXPECT_GT(m.packets(), 0u);
    EXPECT_EQ(m.format_version(), kStreamFormatVersion);
    EXPECT_TRUE(m.has_original());  // kept, so it can be re-encoded
    EXPECT_NE(m.settings().find("precinct="), std::string::npos);
  }
  EXPECT_EQ(ParseList(HttpGet(port_, "/v1/meshes?limit=2").body).meshes_size(), 2);
  const proto::MeshList tail = ParseList(HttpGet(port_, "/v1/meshes?limit=2&offset=3").body);
  ASSERT_EQ(tail.meshes_size(), 1);
  EXPECT_EQ(tail.meshes(0).id(), list.meshes(3).id());
}

TEST_F(ServerHttpTest, ListsCatalogAsProtobuf) {
  const HttpReply r = HttpGet(port_, "/v1/meshes", {{"Accept", "application/x-protobuf"}});
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.Header("content-type"), "application/x-protobuf");
  proto::MeshList list;
  ASSERT_TRUE(list.ParseFromString(r.body));
  EXPECT_EQ(list.meshes_size(), 4);
  EXPECT_EQ(list.total(), 4u);
}

TEST_F(ServerHttpTest, DescribesMeshWithRateDistortionTable) {
  const std::string id = ids_.at("holes_patch");
  const HttpReply r = HttpGet(port_, "/v1/meshes/" + id);
  ASSERT_EQ(r.status, 200u) << r.body;
  proto::MeshDetails d;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &d).ok());
  EXPECT_EQ(d.mesh().id(), id);
  EXPECT_EQ(d.header_bytes() + d.payload_bytes(), d.mesh().bytes());
  ASSERT_EQ(d.orders_size(), 3);
  EXPECT_EQ(d.orders(0).name(), "quality");
  ASSERT_EQ(d.rate_distortion_size(), static_cast<int>(d.mesh().packets()) + 1);
  for (int i = 1; i < d.rate_distortion_size(); ++i) {
    EXPECT_GT(d.rate_distortion(i).bytes(), d.rate_distortion(i - 1).bytes());
    EXPECT_GE(d.rate_distortion(i).psnr_db(), d.rate_distortion(i - 1).psnr_db() - 1e-9);
  }
  EXPECT_EQ(d.rate_distortion(d.rate_distortion_size() - 1).bytes(), d.mesh().bytes());
  // The table's last figure is what a decoder of the whole stream estimates.
  double estimate = 0;
  Decode(Container(id), &estimate);
  EXPECT_NEAR(d.rate_distortion(d.rate_distortion_size() - 1).psnr_db(), estimate, 1e-6);
}

TEST_F(ServerHttpTest, HeaderIsTheContainersStreamHeader) {
  for (const auto& [name, id] : ids_) {
    const HttpReply r = HttpGet(port_, "/v1/meshes/" + id + "/header");
    ASSERT_EQ(r.status, 200u);
    proto::StreamHeader served;
    ASSERT_TRUE(served.ParseFromString(r.body));
    const std::string bytes = Container(id);
    auto parsed = ParseContainer(bytes);
    ASSERT_TRUE(parsed.ok());
    proto::StreamHeader stored;
    ASSERT_TRUE(stored.ParseFromString(parsed->header.bytes_without_present));
    EXPECT_EQ(served.SerializeAsString(), stored.SerializeAsString()) << name;
    EXPECT_EQ(r.body, parsed->header.bytes_without_present) << name;
    auto read = ReadStreamHeader(r.body);
    ASSERT_TRUE(read.ok());
    EXPECT_TRUE(ValidateStreamHeader(*read).ok());
  }
}

TEST_F(ServerHttpTest, StreamDecodesLikeALocalTruncation) {
  for (const auto& [name, id] : ids_) {
    const std::string full = Container(id);
    auto parsed = ParseContainer(full);
    ASSERT_TRUE(parsed.ok());
    StreamHeader header = parsed->header;
    header.present.clear();
    std::map<uint32_t, std::string_view> payloads;
    for (size_t i = 0; i < parsed->ids.size(); ++i) payloads[parsed->ids[i]] = parsed->payloads[i];
    const std::vector<Vec3> reference = Decode(full);
    const double peak = Diagonal(header);
    const uint64_t head = ContainerSize(header, {});
    for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
      const auto order = PacketOrder(header, p);
      for (uint64_t budget : {head, head + 700, full.size() / 3, 2 * full.size() / 3,
                              uint64_t{full.size()}}) {
        const std::string target = "/v1/meshes/" + id + "/stream?order=" + ProgressionName(p) +
                                   "&budget=" + std::to_string(budget);
        const HttpReply r = HttpGet(port_, target);
        ASSERT_EQ(r.status, 200u) << target << " " << r.body;
        // The same truncation made here with the codec library.
        const Selection s = SelectPackets(header, order, budget);
        std::string local = SerializeContainerHead(header, s.ids);
        for (uint32_t k : s.ids) local += payloads.at(k);
        EXPECT_EQ(r.body.size(), local.size()) << target;
        EXPECT_LE(r.body.size(), budget);
        EXPECT_EQ(r.Header("x-meshwave-packets"), std::to_string(s.ids.size()));
        EXPECT_EQ(r.Header("x-meshwave-next-cursor"), std::to_string(s.next_cursor));
        EXPECT_EQ(r.Header("x-meshwave-complete"), s.next_cursor == order.size() ? "true" : "false");
        double served_estimate = 0, local_estimate = 0;
        const double served_psnr = Psnr(reference, Decode(r.body, &served_estimate), peak);
        const double local_psnr = Psnr(reference, Decode(local, &local_estimate), peak);
        EXPECT_EQ(served_psnr, local_psnr) << target;
        EXPECT_EQ(served_estimate, local_estimate) << target;
        EXPECT_EQ(r.body, local) << target;
      }
    }
  }
}

TEST_F(ServerHttpTest, StreamLimitsLevels) {
  const std::string id = ids_.at("holes_copy");
  const std::string bytes = Container(id);
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok());
  const auto order = PacketOrder(parsed->header, Progression::kResolution, 1);
  const HttpReply r = HttpGet(port_, "/v1/meshes/" + id + "/stream?order=resolution&max_level=1");
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.Header("x-meshwave-packets"), std::to_string(order.size()));
  EXPECT_EQ(r.Header("x-meshwave-complete"), "true");
  auto served = ParseContainer(r.body);
  ASSERT_TRUE(served.ok());
  EXPECT_EQ(served->ids, order);
}

TEST_F(ServerHttpTest, StreamContinuesFromCursor) {
  const std::string id = ids_.at("elephant");
  const std::string full = Container(id);
  auto parsed = ParseContainer(full);
  ASSERT_TRUE(parsed.ok());
  StreamHeader header = parsed->header;
  header.present.clear();
  const auto order = PacketOrder(header, Progression::kRd);
  const uint64_t head = ContainerSize(header, {});

  HttpReply first = HttpGet(port_, "/v1/meshes/" + id + "/stream?order=rd&budget=" +
                                       std::to_string(head + 1000));
  ASSERT_EQ(first.status, 200u);
  auto start = ParseContainer(first.body);
  ASSERT_TRUE(start.ok());
  auto decoder = ProgressiveDecoder::Create(start->header);
  ASSERT_TRUE(decoder.ok());
  for (size_t i = 0; i < start->ids.size(); ++i) {
    ASSERT_TRUE((*decoder)->AddPacket(start->ids[i], start->payloads[i]).ok());
  }
  size_t cursor = std::stoul(first.Header("x-meshwave-next-cursor"));
  EXPECT_EQ(cursor, start->ids.size());
  uint64_t budget = 1500;
  bool complete = first.Header("x-meshwave-complete") == "true";
  HttpConnection conn(port_);  // keep-alive: every step on one connection
  while (!complete) {
    const std::string target = "/v1/meshes/" + id + "/stream?order=rd&from=" +
                               std::to_string(cursor) + "&budget=" + std::to_string(budget);
    const HttpReply r = conn.Send(http::verb::get, target);
    ASSERT_EQ(r.status, 200u) << r.body;
    EXPECT_TRUE(r.keep_alive);
    const size_t next = std::stoul(r.Header("x-meshwave-next-cursor"));
    ASSERT_EQ(std::stoul(r.Header("x-meshwave-packets")), next - cursor);
    // Payloads only: split them by the index's lengths.
    std::string_view body = r.body;
    for (size_t k = cursor; k < next; ++k) {
      const uint32_t pid = order[k];
      const size_t length = header.packets.length[pid];
      ASSERT_GE(body.size(), length);
      ASSERT_TRUE((*decoder)->AddPacket(pid, body.substr(0, length)).ok());
      body.remove_prefix(length);
    }
    EXPECT_TRUE(body.empty());
    EXPECT_LE(r.body.size(), budget);
    if (next == cursor) budget *= 2;  // the next packet is larger than the budget
    cursor = next;
    complete = r.Header("x-meshwave-complete") == "true";
  }
  EXPECT_EQ(cursor, order.size());
  double full_estimate = 0;
  const auto reference = Decode(full, &full_estimate);
  EXPECT_EQ((*decoder)->Positions(), reference);
  EXPECT_EQ((*decoder)->EstimatedPsnr(), full_estimate);
}

TEST_F(ServerHttpTest, ServesSinglePackets) {
  const std::string id = ids_.at("holes");
  const std::string bytes = Container(id);
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok());
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    const HttpReply r =
        HttpGet(port_, "/v1/meshes/" + id + "/packets/" + std::to_string(parsed->ids[i]));
    ASSERT_EQ(r.status, 200u);
    EXPECT_EQ(r.body, parsed->payloads[i]);
  }
  const HttpReply past =
      HttpGet(port_, "/v1/meshes/" + id + "/packets/" + std::to_string(parsed->ids.size()));
  EXPECT_EQ(past.status, 404u);
  EXPECT_TRUE(IsJsonError(past));
}

TEST_F(ServerHttpTest, ContainerAnswersRangeRequests) {
  const std::string id = ids_.at("holes_patch");
  const std::string full = Container(id);
  const std::string base = "/v1/meshes/" + id + "/container";
  // Its strong ETag names the container's SHA-256.
  EXPECT_NE(HttpGet(port_, base).Header("etag").find(Sha256Hex(full)), std::string::npos);
  HttpReply r = HttpGet(port_, base, {{"Range", "bytes=10-19"}});
  EXPECT_EQ(r.status, 206u);
  EXPECT_EQ(r.body, full.substr(10, 10));
  EXPECT_EQ(r.Header("content-range"), "bytes 10-19/" + std::to_string(full.size()));
  r = HttpGet(port_, base, {{"Range", "bytes=-5"}});
  EXPECT_EQ(r.status, 206u);
  EXPECT_EQ(r.body, full.substr(full.size() - 5));
  r = HttpGet(port_, base, {{"Range", "bytes=100-"}});
  EXPECT_EQ(r.status, 206u);
  EXPECT_EQ(r.body, full.substr(100));
  r = HttpGet(port_, base, {{"Range", "bytes=" + std::to_string(full.size()) + "-"}});
  EXPECT_EQ(r.status, 416u);
  EXPECT_EQ(r.Header("content-range"), "bytes */" + std::to_string(full.size()));
  EXPECT_TRUE(IsJsonError(r));
  r = HttpGet(port_, base, {{"Range", "bytes=9-3"}});
  EXPECT_EQ(r.status, 416u);
  EXPECT_NE(r.body.find("ends before it starts"), std::string::npos) << r.body;
  r = HttpGet(port_, base, {{"Range", "bytes=0-1,4-5"}});  // several: the whole
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, full);
  EXPECT_EQ(r.Header("accept-ranges"), "bytes");
}

TEST_F(ServerHttpTest, RangeFollowsRfc9110Syntax) {
  const std::string id = ids_.at("holes_patch");
  const std::string full = Container(id);
  const std::string base = "/v1/meshes/" + id + "/container";
  // Case-insensitive unit, empty list elements, whitespace, coalescing.
  for (const char* range : {"BYTES=0-5", "bytes=0-5,", "bytes= 0-5", "bytes=,0-5",
                            "bytes=0-2,3-5", "bytes=0-5,1-4"}) {
    const HttpReply r = HttpGet(port_, base, {{"Range", range}});
    EXPECT_EQ(r.status, 206u) << range;
    EXPECT_EQ(r.body, full.substr(0, 6)) << range;
    EXPECT_EQ(r.Header("content-range"), "bytes 0-5/" + std::to_string(full.size())) << range;
  }
  // A malformed range says what is wrong, not that it "does not fit".
  HttpReply r = HttpGet(port_, base, {{"Range", "bytes=abc"}});
  EXPECT_EQ(r.status, 416u);
  EXPECT_TRUE(IsJsonError(r));
  EXPECT_NE(r.body.find("not first-last, first- or -suffix"), std::string::npos) << r.body;
  EXPECT_EQ(r.Header("content-range"), "bytes */" + std::to_string(full.size()));
  // Another unit: ignored.
  r = HttpGet(port_, base, {{"Range", "items=0-5"}});
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, full);
}

TEST_F(ServerHttpTest, IfRangeDecidesBetweenPartAndWhole) {
  const std::string id = ids_.at("holes_patch");
  const std::string base = "/v1/meshes/" + id + "/container";
  const HttpReply whole = HttpGet(port_, base);
  const std::string etag = whole.Header("etag");
  ASSERT_FALSE(etag.empty());
  ASSERT_TRUE(whole.Header("last-modified").empty());  // so no date can validate
  const auto get = [&](const std::string& if_range) {
    return HttpGet(port_, base, {{"Range", "bytes=10-19"}, {"If-Range", if_range}});
  };
  // The same strong tag: the range (RFC 9110 13.1.5).
  HttpReply r = get(etag);
  EXPECT_EQ(r.status, 206u);
  EXPECT_EQ(r.body, whole.body.substr(10, 10));
  // Any other validator: the whole representation with 200, as if no Range.
  for (const std::string& other : {"W/" + etag, std::string("\"0123\""),
                                  std::string("Sun, 06 Nov 1994 08:49:37 GMT"),
                                  std::string("not a validator")}) {
    r = get(other);
    EXPECT_EQ(r.status, 200u) << other;
    EXPECT_EQ(r.body, whole.body) << other;
    EXPECT_TRUE(r.Header("content-range").empty()) << other;
  }
  // A failed If-Range also keeps an unsatisfiable range from giving 416.
  r = HttpGet(port_, base, {{"Range", "bytes=999999999-"}, {"If-Range", "\"other\""}});
  EXPECT_EQ(r.status, 200u);
  // If-Range without Range is ignored.
  r = HttpGet(port_, base, {{"If-Range", etag}});
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, whole.body);
  // If-None-Match is evaluated first (RFC 9110 13.2.2): 304.
  r = HttpGet(port_, base, {{"Range", "bytes=10-19"}, {"If-Range", etag}, {"If-None-Match", etag}});
  EXPECT_EQ(r.status, 304u);
}

TEST_F(ServerHttpTest, ImmutableResourcesAnswerIfNoneMatch) {
  const std::string id = ids_.at("holes_copy");
  for (const std::string suffix : {"/header", "/container", "/packets/0",
                                   "/stream?order=quality&budget=9000", ""}) {
    const std::string target = "/v1/meshes/" + id + suffix;
    const HttpReply r = HttpGet(port_, target);
    ASSERT_EQ(r.status, 200u) << target;
    const std::string etag = r.Header("etag");
    ASSERT_FALSE(etag.empty()) << target;
    EXPECT_EQ(etag.front(), '"');  // strong
    EXPECT_EQ(r.Header("cache-control"), "public, max-age=31536000, immutable");
    HttpReply again = HttpGet(port_, target, {{"If-None-Match", etag}});
    EXPECT_EQ(again.status, 304u) << target;
    EXPECT_TRUE(again.body.empty());
    EXPECT_EQ(again.Header("etag"), etag);
    again = HttpGet(port_, target, {{"If-None-Match", "\"other\", W/" + etag}});
    EXPECT_EQ(again.status, 304u) << target;
    again = HttpGet(port_, target, {{"If-None-Match", "\"other\""}});
    EXPECT_EQ(again.status, 200u) << target;
  }
  // Another stream query gives other bytes, so another tag (both budgets
  // inside the 7.7 KB stream).
  const auto a = HttpGet(port_, "/v1/meshes/" + id + "/stream?budget=4000").Header("etag");
  const auto b = HttpGet(port_, "/v1/meshes/" + id + "/stream?budget=6000").Header("etag");
  EXPECT_NE(a, b);
}

// Repeated GETs of the mesh endpoints come from the response cache: the
// same status, headers and bytes as the first answer, also on one
// keep-alive connection; HEAD and HTTP/1.0 get the same head with their own
// Connection field; a Range is part of the key; a DELETE ends them.
TEST_F(ServerHttpTest, CachedResponsesAreTheSameAndEndWithTheMesh) {
  const std::string id = ids_.at("holes_copy");
  const std::string base = "/v1/meshes/" + id;
  for (const std::string suffix : {"/packets/0", "/packets/3", "/stream?order=quality&budget=9000",
                                   "/stream?order=resolution&from=1&budget=3000", "/header",
                                   "/container"}) {
    const std::string target = base + suffix;
    HttpConnection c(port_);
    const HttpReply first = c.Send(http::verb::get, target);
    ASSERT_EQ(first.status, 200u) << target;
    for (int i = 0; i < 3; ++i) {
      const HttpReply again = c.Send(http::verb::get, target);
      EXPECT_EQ(again.status, first.status) << target;
      EXPECT_EQ(again.headers, first.headers) << target;
      EXPECT_EQ(again.body, first.body) << target;
      EXPECT_TRUE(again.keep_alive);
    }
    const HttpReply head = c.Send(http::verb::head, target);
    EXPECT_EQ(head.status, 200u);
    EXPECT_EQ(head.headers, first.headers) << target;
    EXPECT_TRUE(head.body.empty());
    HttpConnection old(port_);
    const HttpReply http10 = old.SendRaw("GET " + target + " HTTP/1.0\r\n\r\n");
    EXPECT_EQ(http10.status, 200u);
    EXPECT_EQ(http10.body, first.body);
    EXPECT_FALSE(http10.keep_alive);
    EXPECT_TRUE(old.ClosedByServer());
  }
  HttpConnection c(port_);
  const std::string whole = c.Send(http::verb::get, base + "/container").body;
  for (int i = 0; i < 2; ++i) {
    const HttpReply part = c.Send(http::verb::get, base + "/container", {{"Range", "bytes=10-19"}});
    EXPECT_EQ(part.status, 206u);
    EXPECT_EQ(part.body, whole.substr(10, 10));
    EXPECT_EQ(part.Header("content-range"), "bytes 10-19/" + std::to_string(whole.size()));
    EXPECT_EQ(c.Send(http::verb::get, base + "/container").body, whole);
  }
  const std::pair<std::string, std::string> auth = {"Authorization", std::string("Bearer ") + kToken};
  EXPECT_EQ(HttpConnection(port_).Send(http::verb::delete_, base, {auth}).status, 204u);
  for (const std::string suffix : {"/packets/0", "/stream?order=quality&budget=9000", "/container"}) {
    EXPECT_EQ(c.Send(http::verb::get, base + suffix).status, 404u) << suffix;
  }
}

TEST_F(ServerHttpTest, BadRequestsGetJsonErrorsAndServerStaysUp) {
  const std::string id = ids_.at("holes");
  const std::string m = "/v1/meshes/" + id;
  const std::vector<std::pair<std::string, unsigned>> corpus = {
      {"GET /v1/meshes/xyz HTTP/1.1", 400},
      {"GET /v1/meshes/0123456789AB HTTP/1.1", 400},
      {"GET /v1/meshes/0123456789ab0 HTTP/1.1", 400},
      {"GET /v1/meshes/000000000000 HTTP/1.1", 404},
      {"GET /v1/meshes/../../etc/passwd HTTP/1.1", 400},
      {"GET /v1/meshes/%2e%2e/%2e%2e/etc/passwd HTTP/1.1", 400},
      {"GET /v1/meshes/" + id + "%2f..%2f HTTP/1.1", 400},
      {"GET /v1/meshes/%00 HTTP/1.1", 400},
      {"GET " + m + "/stream?budget=-1 HTTP/1.1", 400},
      {"GET " + m + "/stream?budget=abc HTTP/1.1", 400},
      {"GET " + m + "/stream?budget=99999999999999999999999999 HTTP/1.1", 400},
      {"GET " + m + "/stream?budget=18446744073709551616 HTTP/1.1", 400},
      {"GET " + m + "/stream?budget=10 HTTP/1.1", 400},  // below the header
      {"GET " + m + "/stream?order=best HTTP/1.1", 400},
      {"GET " + m + "/stream?max_level=99 HTTP/1.1", 400},
      {"GET " + m + "/stream?from=999999 HTTP/1.1", 400},
      {"GET " + m + "/stream?from=-1 HTTP/1.1", 400},
      {"GET " + m + "/stream?evil=1 HTTP/1.1", 400},
      {"GET " + m + "/packets/-1 HTTP/1.1", 400},
      {"GET " + m + "/packets/99999999999 HTTP/1.1", 400},
      {"GET " + m + "/packets/1000 HTTP/1.1", 404},
      {"GET " + m + "/bogus HTTP/1.1", 404},
      {"GET " + m + "/header?x=1 HTTP/1.1", 400},
      {"GET /v1/nothing HTTP/1.1", 404},
      {"GET /v2/meshes HTTP/1.1", 404},
      {"GET /v1/meshes?limit=100000 HTTP/1.1", 400},
      {"GET /v1/meshes?limit=-5 HTTP/1.1", 400},
      {"GET /v1/meshes?foo=1 HTTP/1.1", 400},
      {"GET relative/path HTTP/1.1", 400},
      {"PUT " + m + " HTTP/1.1", 405},
      {"POST " + m + "/header HTTP/1.1\r\nContent-Length: 0", 405},
      {"DELETE /healthz HTTP/1.1", 405},
      {"PATCH /v1/meshes HTTP/1.1", 405},
      {"GET /v1/meshes HTTP/1.1\r\nContent-Length: 10000000", 413},
      {"GET /healthz HTTP/1.1\r\nX-Big: " + std::string(64 * 1024, 'a'), 431},
      {"HELLO", 400},
      {"GET /v1/meshes HTTP/9.9", 400},
      {"GET /v1/meshes HTTP/1.1\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
       "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==", 404},
      {"GET /v1/ws HTTP/1.1", 426},
  };
  for (const auto& [request, expected] : corpus) {
    HttpConnection c(port_);
    ASSERT_TRUE(c.connected());
    const HttpReply r = c.SendRaw(request + "\r\nHost: x\r\n\r\n");
    EXPECT_EQ(r.status, expected) << request.substr(0, 120);
    EXPECT_TRUE(IsJsonError(r)) << request.substr(0, 120) << " -> " << r.body;
  }
  const HttpReply health = HttpGet(port_, "/healthz");
  EXPECT_EQ(health.status, 200u);
  EXPECT_EQ(HttpGet(port_, "/v1/meshes").status, 200u);
}

TEST_F(ServerHttpTest, MetricsCountRequests) {
  HttpGet(port_, "/v1/meshes");
  HttpGet(port_, "/v1/nothing");
  // A request is counted when its write completes on the server, which may
  // be just after the client has read the response: ask until the 404 shows
  // (a slow sanitizer build hit that window), but at most for a few seconds.
  const std::string not_found = "meshwave_http_requests_total{code=\"404\"} 1\n";
  HttpReply r;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  do {
    r = HttpGet(port_, "/metrics");
    ASSERT_EQ(r.status, 200u);
    if (r.body.find(not_found) != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (std::chrono::steady_clock::now() < deadline);
  EXPECT_NE(r.body.find("meshwave_http_requests_total{code=\"200\"}"), std::string::npos);
  EXPECT_NE(r.body.find(not_found), std::string::npos);
  EXPECT_NE(r.body.find("meshwave_http_request_duration_seconds_bucket{le=\"+Inf\"}"),
            std::string::npos);
  EXPECT_NE(r.body.find("meshwave_http_response_bytes_total "), std::string::npos);
  EXPECT_NE(r.body.find("meshwave_catalog_meshes 4"), std::string::npos);
  EXPECT_NE(r.body.find("meshwave_websocket_connections 0"), std::string::npos);
}

TEST_F(ServerHttpTest, HeadAnswersWithoutBody) {
  HttpConnection c(port_);
  const std::string id = ids_.at("holes");
  const HttpReply r = c.Send(http::verb::head, "/v1/meshes/" + id + "/container");
  EXPECT_EQ(r.status, 200u);
  EXPECT_TRUE(r.body.empty());
  EXPECT_EQ(r.Header("content-length"), std::to_string(Container(id).size()));
}

TEST_F(ServerHttpTest, StopsGracefullyWithIdleConnectionsOpen) {
  HttpConnection idle(port_);
  ASSERT_EQ(idle.Send(http::verb::get, "/healthz").status, 200u);  // keep-alive
  EXPECT_EQ(server_->Stop(), 0) << ReadBytes(server_->log());
  EXPECT_TRUE(idle.ClosedByServer());
  server_.reset();
}

TEST_F(ServerHttpTest, RefusesConnectionsPastTheCap) {
  const auto dir = tmp_ / "capped";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "server.conf") << "max_connections: 2\nidle_timeout_seconds: 20\n";
  ServerProcess capped(catalog_, dir, {}, {"--config", (dir / "server.conf").string()});
  ASSERT_TRUE(capped.running()) << ReadBytes(capped.log());
  HttpConnection a(capped.port()), b(capped.port());
  ASSERT_EQ(a.Send(http::verb::get, "/healthz").status, 200u);
  ASSERT_EQ(b.Send(http::verb::get, "/healthz").status, 200u);
  HttpConnection c(capped.port());
  const HttpReply refused = c.Send(http::verb::get, "/healthz");
  EXPECT_EQ(refused.status, 503u);
  EXPECT_TRUE(IsJsonError(refused));
  EXPECT_EQ(a.Send(http::verb::get, "/healthz").status, 200u);  // the others still work
  EXPECT_EQ(capped.Stop(), 0);
}

}  // namespace
}  // namespace meshwave::testing
