// Region requests (docs/API.md, "Region requests") against the real
// meshwave-server on 127.0.0.1, over GET /stream and the WebSocket: any
// sequence of region and uniform requests sends every unit once and ends in
// exactly the complete stream's mesh; the region comes first; the same
// selection over both; refusals.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "catalog_api.pb.h"
#include "core/base64.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "meshwave/container.h"
#include "meshwave/progressive_decoder.h"
#include "region_receiver_testonly.h"
#include "sample_catalog_testonly.h"
#include "server_process_testonly.h"
#include "test_data.h"
#include "websocket.pb.h"
#include "ws_client_testonly.h"

namespace meshwave::testing {
namespace {

// The elephant with small precincts, so that its finer subbands have tens
// of them and their low bitplanes are split.
class ServerRegionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const auto catalog = *dir_ / "catalog";
    ASSERT_NO_FATAL_FAILURE(CopySampleCatalog(catalog, {SampleMesh("elephant.off")},
                                              // Without the original layer, global
                                              // and last (docs/FORMAT.md 2.5).
                                              {"--precinct-size", "48", "--split-bytes", "4",
                                               "--no-original"}));
    std::filesystem::create_directories(*dir_ / "server");
    server_ = new ServerProcess(catalog, *dir_ / "server");
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    proto::MeshList meshes;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(
                    HttpGet(server_->port(), "/v1/meshes").body, &meshes)
                    .ok());
    ASSERT_EQ(meshes.meshes_size(), 1);
    id_ = new std::string(meshes.meshes(0).id());
    header_ = new std::string(HttpGet(server_->port(), Path("/header")).body);
    // The complete stream's mesh, and a sphere around one side of it.
    const std::string full = HttpGet(server_->port(), Path("/container")).body;
    auto parsed = ParseContainer(full);
    ASSERT_TRUE(parsed.ok());
    auto d = ProgressiveDecoder::Create(parsed->header);
    ASSERT_TRUE(d.ok());
    for (size_t i = 0; i < parsed->ids.size(); ++i) {
      ASSERT_TRUE((*d)->AddPacket(parsed->ids[i], parsed->payloads[i]).ok());
    }
    full_ = new std::vector<Vec3>((*d)->Positions());
    Vec3 lo = full_->front(), hi = full_->front();
    for (const Vec3& p : *full_) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    diagonal_ = (hi - lo).norm();
    // Around the vertex farthest along +x (the trunk or a foot).
    centre_ = new Vec3(*std::max_element(full_->begin(), full_->end(),
                                         [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); }));
    radius_ = 0.2 * diagonal_;
    for (std::string_view p : parsed->payloads) payload_ += p.size();
  }
  static void TearDownTestSuite() {
    if (server_) {
      EXPECT_EQ(server_->Stop(), 0) << ReadBytes(server_->log());
    }
    delete server_;
    delete dir_;
  }

  static std::string Path(const std::string& rest) { return "/v1/meshes/" + *id_ + rest; }
  static HttpReply Stream(const std::string& query) {
    return HttpGet(server_->port(), Path("/stream?" + query));
  }
  static std::string Sphere() {
    return std::to_string(centre_->x()) + "," + std::to_string(centre_->y()) + "," +
           std::to_string(centre_->z()) + "," + std::to_string(radius_);
  }
  // A camera outside the mesh looking at its other side.
  static std::string View() {
    return std::to_string(-centre_->x()) + ",0," + std::to_string(3 * diagonal_) +
           ",0,0,-1,40,800,600";
  }
  // RMS distance to the complete mesh over the vertices inside the sphere.
  static double RegionError(const std::vector<Vec3>& positions) {
    double sse = 0;
    size_t n = 0;
    for (size_t i = 0; i < full_->size(); ++i) {
      if (((*full_)[i] - *centre_).norm() > radius_) continue;
      sse += (positions[i] - (*full_)[i]).squaredNorm();
      ++n;
    }
    EXPECT_GT(n, 10u);
    return std::sqrt(sse / static_cast<double>(n));
  }

  static inline TempDir* dir_ = nullptr;
  static inline ServerProcess* server_ = nullptr;
  static inline std::string* id_ = nullptr;
  static inline std::string* header_ = nullptr;
  static inline std::vector<Vec3>* full_ = nullptr;
  static inline Vec3* centre_ = nullptr;
  static inline double radius_ = 0, diagonal_ = 0;
  static inline uint64_t payload_ = 0;  // every packet's
  // A share of the payload bytes, as a decimal budget.
  static std::string Share(double share) {
    return std::to_string(static_cast<uint64_t>(share * static_cast<double>(payload_)));
  }
};

TEST_F(ServerRegionTest, HttpSequenceOfRegionsAndOrdersSendsEveryUnitOnceAndEndsInTheFullMesh) {
  RegionReceiver rx(*header_);
  ASSERT_GT(rx.numbering().size(), rx.header().packets.length.size() + 50)
      << "the fixture should have split packets";
  // Each request, and whether it must bring units and leave nothing (below
  // its level limit).
  struct Step {
    std::string query;
    bool brings;
    bool complete;
  };
  const std::vector<Step> steps = {
      {"region=" + Sphere() + "&budget=" + Share(0.05), true, false},
      {"view=" + View() + "&budget=" + Share(0.05), true, false},
      {"order=rd&budget=" + Share(0.05), true, false},
      {"region=" + Sphere() + "&budget=" + Share(0.1), true, false},
      {"view=" + View() + "&screen_error=0.1&budget=1", false, false},  // nothing fits
      {"order=resolution&max_level=1", true, true},
      {"region=" + Sphere(), true, true}};
  for (const Step& step : steps) {
    const std::string& q = step.query;
    const HttpReply r = Stream(q + "&held=" + rx.Held());
    ASSERT_EQ(r.status, 200u) << q << ": " << r.body;
    EXPECT_EQ(r.Header("content-type"), "application/vnd.meshwave.units");
    const size_t before = rx.units();
    const Status s = rx.ReceiveBody(r.body);
    ASSERT_TRUE(s.ok()) << q << ": " << s.ToString();
    EXPECT_EQ(r.Header("x-meshwave-units"), std::to_string(rx.units() - before)) << q;
    EXPECT_EQ(r.Header("x-meshwave-complete"), step.complete ? "true" : "false") << q;
    EXPECT_EQ(rx.units() > before, step.brings) << q;
  }
  EXPECT_TRUE(rx.AllHeld());
  EXPECT_GT(rx.parts(), 50u);
  EXPECT_EQ(rx.decoder().Positions(), *full_);
  // Nothing left: an empty body, complete.
  const HttpReply again = Stream("region=" + Sphere() + "&held=" + rx.Held());
  EXPECT_EQ(again.status, 200u);
  EXPECT_EQ(again.body, "");
  EXPECT_EQ(again.Header("x-meshwave-complete"), "true");
}

TEST_F(ServerRegionTest, HttpRegionIsFarCloserThanTheRdOrderAtEqualBytes) {
  // rd's container at a budget, and the region's units for the same
  // payload bytes.
  const HttpReply rd = Stream("order=rd&budget=" + std::to_string(header_->size() + payload_ / 2));
  ASSERT_EQ(rd.status, 200u);
  auto parsed = ParseContainer(rd.body);
  ASSERT_TRUE(parsed.ok());
  uint64_t payload = 0;
  RegionReceiver by_rd(*header_);
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    payload += parsed->payloads[i].size();
    ASSERT_TRUE(by_rd.Receive({parsed->ids[i]}, parsed->payloads[i]).ok());
  }
  RegionReceiver by_region(*header_);
  const HttpReply region = Stream("region=" + Sphere() + "&budget=" + std::to_string(payload));
  ASSERT_EQ(region.status, 200u) << region.body;
  ASSERT_TRUE(by_region.ReceiveBody(region.body).ok());
  EXPECT_LE(region.body.size(), payload + 12 * by_region.units());
  const double rd_error = RegionError(by_rd.decoder().Positions());
  const double region_error = RegionError(by_region.decoder().Positions());
  EXPECT_LT(region_error, 0.5 * rd_error) << "rd " << rd_error << ", region " << region_error;
}

// A view with a screen-space error: the units that bring what the camera
// sees within the tolerance, then complete; asked again, nothing; without
// the tolerance, the same view brings the rest.
TEST_F(ServerRegionTest, HttpScreenErrorStopsWhenTheViewIsWithinIt) {
  RegionReceiver rx(*header_);
  const HttpReply first = Stream("view=" + View() + "&screen_error=2&held=" + rx.Held());
  ASSERT_EQ(first.status, 200u) << first.body;
  ASSERT_TRUE(rx.ReceiveBody(first.body).ok());
  EXPECT_EQ(first.Header("x-meshwave-complete"), "true");
  EXPECT_GT(rx.units(), 0u);
  EXPECT_FALSE(rx.AllHeld());
  EXPECT_LT(first.body.size(), payload_ / 2);
  const HttpReply again = Stream("view=" + View() + "&screen_error=2&held=" + rx.Held());
  ASSERT_EQ(again.status, 200u) << again.body;
  EXPECT_EQ(again.body, "");
  EXPECT_EQ(again.Header("x-meshwave-complete"), "true");
  // A tighter tolerance asks for more.
  const size_t at_two = rx.units();
  const HttpReply finer = Stream("view=" + View() + "&screen_error=0.25&held=" + rx.Held());
  ASSERT_EQ(finer.status, 200u) << finer.body;
  ASSERT_TRUE(rx.ReceiveBody(finer.body).ok());
  EXPECT_GT(rx.units(), at_two);
  const HttpReply rest = Stream("view=" + View() + "&held=" + rx.Held());
  ASSERT_EQ(rest.status, 200u) << rest.body;
  ASSERT_TRUE(rx.ReceiveBody(rest.body).ok());
  EXPECT_TRUE(rx.AllHeld());
  EXPECT_EQ(rx.decoder().Positions(), *full_);
}

TEST_F(ServerRegionTest, HttpRefusesBadRegionsAndHeldSets) {
  const std::string sphere = "region=" + Sphere();
  for (const std::string& q :
       {sphere + "&view=" + View(), sphere + "&screen_error=2", std::string("region=1,2,3,0"),
        std::string("view=0,0,1,0,0,0,45,800,600"), sphere + "&from=3", sphere + "&held=a+b",
        sphere + "&held=_____________________________________________________", sphere + "&max_level=9",
        sphere + "&held=AQ==",  // base64url without padding
        sphere + "&order=rd",   // an order beside a region
        "view=" + View() + "&screen_error=-1"}) {
    const HttpReply r = Stream(q);
    EXPECT_EQ(r.status, 400u) << q << ": " << r.body;
    EXPECT_NE(r.body.find("\"error\""), std::string::npos) << q;
  }
  // A held set not closed under the dependencies: the last unit alone.
  RegionReceiver rx(*header_);
  const size_t last = rx.numbering().size() - 1;
  std::string bitmap(last / 8 + 1, '\0');
  bitmap.back() = static_cast<char>(1u << (last % 8));
  const std::string text = Base64Url(bitmap);
  const HttpReply r = Stream("order=rd&held=" + text);
  EXPECT_EQ(r.status, 400u) << r.body;
  EXPECT_NE(r.body.find("depends on"), std::string::npos) << r.body;
  // At most ceil(units / 8) bytes: trailing zero bytes within that are
  // accepted, one more (even zero) is refused.
  std::string first((rx.numbering().size() + 7) / 8, '\0');
  first[0] = 1;
  EXPECT_EQ(Stream("order=rd&held=" + Base64Url(first)).status, 200u);
  first.push_back('\0');
  const HttpReply longer = Stream("order=rd&held=" + Base64Url(first));
  EXPECT_EQ(longer.status, 400u) << longer.body;
}

// --- WebSocket ---

proto::ClientMessage Start(const std::string& id, const std::string& region, uint64_t budget) {
  proto::ClientMessage m;
  m.mutable_start()->set_mesh_id(id);
  m.mutable_start()->set_region(region);
  m.mutable_start()->set_budget(budget);
  return m;
}

// Feeds what one request brought to `rx`; its Done, checked for shape.
proto::Done Take(WsTestClient& c, const proto::ClientMessage& request, RegionReceiver* rx,
                 std::string* header = nullptr) {
  EXPECT_TRUE(c.Send(request));
  proto::Done done;
  proto::Selection selection;
  size_t packets = 0;
  for (const auto& m : c.ReadUntilDone()) {
    EXPECT_FALSE(m.has_error()) << m.error().message();
    if (m.has_start()) {
      if (header) *header = m.start().header();
      selection = m.start().selection();
    }
    if (m.has_selection()) selection = m.selection();
    if (m.has_packet()) {
      EXPECT_EQ(m.packet().cursor(), selection.from_cursor() + packets++);
      const StreamUnit u{m.packet().id(),
                         m.packet().has_part() ? m.packet().part() : StreamUnit::kWholePacket};
      if (rx) {
        const Status s = rx->Receive(u, m.packet().payload());
        EXPECT_TRUE(s.ok()) << s.ToString();
      }
    }
    if (m.has_done()) done = m.done();
  }
  EXPECT_EQ(selection.next_cursor(), selection.from_cursor() + packets);
  EXPECT_EQ(done.next_cursor(), selection.next_cursor());
  return done;
}

TEST_F(ServerRegionTest, WebSocketSequenceSendsEveryUnitOnceAcrossAResumeAndEndsInTheFullMesh) {
  RegionReceiver rx(*header_);
  WsTestClient c(server_->port());
  ASSERT_TRUE(c.open());
  std::string header;
  proto::Done done = Take(c, Start(*id_, Sphere(), header_->size() + payload_ / 20), &rx, &header);
  EXPECT_EQ(header, *header_);
  EXPECT_GT(rx.parts(), 0u);
  proto::ClientMessage refine;
  refine.mutable_refine()->set_extra_bytes(payload_ / 20);
  refine.mutable_refine()->set_view(View());
  done = Take(c, refine, &rx);
  proto::ClientMessage plain;
  plain.mutable_refine()->set_extra_bytes(payload_ / 20);
  done = Take(c, plain, &rx);  // the view again
  proto::ClientMessage rd;
  rd.mutable_refine()->set_extra_bytes(payload_ / 20);
  rd.mutable_refine()->set_order("rd");
  done = Take(c, rd, &rx);
  EXPECT_FALSE(done.complete());
  // A new connection: the rest, named by what is held.
  WsTestClient c2(server_->port());
  ASSERT_TRUE(c2.open());
  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id(*id_);
  resume.mutable_resume()->set_held(rx.Held());
  resume.mutable_resume()->set_region(Sphere());
  resume.mutable_resume()->set_budget(payload_ / 10);
  done = Take(c2, resume, &rx);
  EXPECT_FALSE(done.complete());
  proto::ClientMessage rest;
  rest.mutable_refine()->set_extra_bytes(uint64_t{1} << 40);
  rest.mutable_refine()->set_order("quality");
  done = Take(c2, rest, &rx);
  EXPECT_TRUE(done.complete());
  EXPECT_TRUE(rx.AllHeld());
  EXPECT_EQ(rx.decoder().Positions(), *full_);
}

TEST_F(ServerRegionTest, WebSocketRefineWithARegionContinuesAStreamOfPacketsWithoutResending) {
  RegionReceiver rx(*header_);
  WsTestClient c(server_->port());
  ASSERT_TRUE(c.open());
  proto::ClientMessage start;
  start.mutable_start()->set_mesh_id(*id_);
  start.mutable_start()->set_order("quality");
  start.mutable_start()->set_budget(header_->size() + payload_ / 10);
  proto::Done done = Take(c, start, &rx);
  const size_t packets = rx.units();
  ASSERT_GT(packets, 5u);
  proto::ClientMessage refine;
  refine.mutable_refine()->set_extra_bytes(uint64_t{1} << 40);
  refine.mutable_refine()->set_region(Sphere());
  done = Take(c, refine, &rx);  // cursors go on from the packets sent
  EXPECT_TRUE(done.complete());
  EXPECT_TRUE(rx.AllHeld());
  EXPECT_EQ(rx.decoder().Positions(), *full_);
}

TEST_F(ServerRegionTest, WebSocketStartSelectsWhatGetStreamSelects) {
  for (uint64_t payload : {payload_ / 30, payload_ / 5}) {
    RegionReceiver by_ws(*header_);
    WsTestClient c(server_->port());
    ASSERT_TRUE(c.open());
    // The start's budget counts the header as a container's does.
    const uint64_t header_cost = ContainerSize(by_ws.header(), {});
    Take(c, Start(*id_, Sphere(), header_cost + payload), &by_ws);
    RegionReceiver by_http(*header_);
    const HttpReply r = Stream("region=" + Sphere() + "&budget=" + std::to_string(payload));
    ASSERT_TRUE(by_http.ReceiveBody(r.body).ok());
    EXPECT_EQ(by_ws.Held(), by_http.Held()) << payload;
    EXPECT_EQ(by_ws.units(), by_http.units());
  }
}

// docs/API.md, WebSocket: a start's budget for units counts the header's
// container (8 bytes of magic and length, then the header) and the units'
// payloads; Selection.bytes counts the same (the header at a start, the
// payloads; no message framing and, unlike GET /stream's Content-Length,
// no record heads); a resume on a new connection starts its cursors at 0.
TEST_F(ServerRegionTest, WebSocketUnitBudgetsSelectionBytesAndCursorsAreAsDocumented) {
  RegionReceiver probe(*header_);
  const uint64_t header_cost = ContainerSize(probe.header(), {});
  EXPECT_EQ(header_cost, 8 + header_->size());
  // What GET /stream sends for a payload budget: its units' payload bytes.
  const HttpReply r = Stream("region=" + Sphere() + "&budget=" + Share(0.1));
  uint64_t payloads = 0, records = 0;
  UnitRecordReader reader(uint64_t{1} << 32, [&](StreamUnit, std::string_view p) {
    payloads += p.size();
    ++records;
    return Status::Ok();
  });
  ASSERT_TRUE(reader.Feed(r.body).ok());
  ASSERT_GT(records, 3u);
  EXPECT_GT(r.body.size(), payloads);  // Content-Length counts the record heads too
  for (const uint64_t budget : {header_cost + payloads, header_cost + payloads - 1}) {
    WsTestClient c(server_->port());
    ASSERT_TRUE(c.open());
    ASSERT_TRUE(c.Send(Start(*id_, Sphere(), budget)));
    proto::Selection selection;
    uint64_t got = 0;
    size_t packets = 0;
    for (const auto& m : c.ReadUntilDone()) {
      ASSERT_FALSE(m.has_error()) << m.error().message();
      if (m.has_start()) selection = m.start().selection();
      if (m.has_packet()) {
        got += m.packet().payload().size();
        ++packets;
      }
    }
    if (budget == header_cost + payloads) {
      EXPECT_EQ(packets, records);  // exactly what fits with the header
      EXPECT_EQ(got, payloads);
    } else {
      EXPECT_LT(packets, records);  // one byte less: the last unit does not fit
    }
    EXPECT_EQ(selection.bytes(), header_cost + got);
  }
  // A refine counts payloads; a resume on a new connection, held units
  // named, starts its cursors at 0.
  RegionReceiver rx(*header_);
  {
    WsTestClient c(server_->port());
    ASSERT_TRUE(c.open());
    Take(c, Start(*id_, Sphere(), header_cost + payloads), &rx);
    proto::ClientMessage refine;
    refine.mutable_refine()->set_extra_bytes(payload_ / 20);
    ASSERT_TRUE(c.Send(refine));
    uint64_t got = 0;
    proto::Selection selection;
    for (const auto& m : c.ReadUntilDone()) {
      if (m.has_selection()) selection = m.selection();
      if (m.has_packet()) {
        got += m.packet().payload().size();
        const StreamUnit u{m.packet().id(),
                           m.packet().has_part() ? m.packet().part() : StreamUnit::kWholePacket};
        ASSERT_TRUE(rx.Receive(u, m.packet().payload()).ok());
      }
    }
    EXPECT_EQ(selection.from_cursor(), records);
    EXPECT_EQ(selection.bytes(), got);
  }
  WsTestClient c(server_->port());
  ASSERT_TRUE(c.open());
  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id(*id_);
  resume.mutable_resume()->set_held(rx.Held());
  resume.mutable_resume()->set_region(Sphere());
  resume.mutable_resume()->set_budget(payload_ / 20);
  ASSERT_TRUE(c.Send(resume));
  uint64_t got = 0;
  size_t packets = 0;
  proto::Selection selection;
  proto::Done done;
  for (const auto& m : c.ReadUntilDone()) {
    ASSERT_FALSE(m.has_error()) << m.error().message();
    if (m.has_selection()) selection = m.selection();
    if (m.has_packet()) {
      EXPECT_EQ(m.packet().cursor(), packets++);
      got += m.packet().payload().size();
    }
    if (m.has_done()) done = m.done();
  }
  ASSERT_GT(packets, 0u);
  EXPECT_EQ(selection.from_cursor(), 0u);
  EXPECT_EQ(selection.next_cursor(), packets);
  EXPECT_EQ(done.next_cursor(), packets);
  EXPECT_EQ(selection.bytes(), got);  // no header in a resume
}

TEST_F(ServerRegionTest, WebSocketRefusesBadRegionRequestsAndStaysOpen) {
  WsTestClient c(server_->port());
  ASSERT_TRUE(c.open());
  std::vector<proto::ClientMessage> bad;
  bad.push_back(Start(*id_, "1,2,3", 5000));  // three numbers
  bad.push_back(Start(*id_, Sphere(), 10));    // below the header
  bad.emplace_back(Start(*id_, Sphere(), 5000));
  bad.back().mutable_start()->set_order("rd");
  bad.emplace_back(Start(*id_, Sphere(), 5000));
  bad.back().mutable_start()->set_view(View());
  bad.emplace_back(Start(*id_, Sphere(), 5000));
  bad.back().mutable_start()->set_screen_error(2);
  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id(*id_);
  resume.mutable_resume()->set_cursor(3);
  resume.mutable_resume()->set_held("AQ");
  bad.push_back(resume);
  resume.mutable_resume()->set_cursor(0);
  resume.mutable_resume()->set_held("not base64!");
  bad.push_back(resume);
  for (const auto& m : bad) {
    ASSERT_TRUE(c.Send(m));
    auto reply = c.Read();
    ASSERT_TRUE(reply.has_value()) << m.DebugString();
    ASSERT_TRUE(reply->has_error()) << m.DebugString();
    EXPECT_EQ(reply->error().code(), proto::Error::BAD_REQUEST) << reply->error().message();
  }
  RegionReceiver rx(*header_);
  EXPECT_TRUE(Take(c, Start(*id_, Sphere(), header_->size() + 2000), &rx).next_cursor() > 0);
}

}  // namespace
}  // namespace meshwave::testing
