// The client end to end: `meshwave fetch`, `refine` and `catalog` against a
// real meshwave-server on 127.0.0.1 (holes.off and elephant.off ingested
// once), directly or through a loopback proxy that cuts, stalls or corrupts.
#include <gtest/gtest.h>

#include <google/protobuf/util/json_util.h>
#include <signal.h>

#include <map>
#include <memory>
#include <thread>

#include "catalog_api.pb.h"
#include "client_state.pb.h"
#include "e2e/cli_runner.h"
#include "meshwave/client/blocking_session.h"
#include "meshwave.pb.h"
#include "meshwave/container.h"
#include "meshwave/mesh_asset.h"
#include "server/http_client_testonly.h"
#include "server/sample_catalog_testonly.h"
#include "server/server_process_testonly.h"
#include "tcp_proxy_testonly.h"
#include "websocket.pb.h"

namespace meshwave {
namespace {

using testing::HttpGet;
using testing::ReadBytes;
using testing::RunCli;
using testing::ServerProcess;
using testing::TcpProxy;
using testing::TempDir;

proto::FetchReport ParseReport(const std::string& json) {
  proto::FetchReport r;
  google::protobuf::util::JsonParseOptions o;
  o.ignore_unknown_fields = true;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &r, o).ok())
      << json;
  return r;
}

void WriteFile(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// Sum of X-Meshwave-Packets over the responses in a proxy transcript.
size_t PacketsAnnounced(const std::string& transcript) {
  size_t total = 0;
  const std::string key = "X-Meshwave-Packets: ";
  for (size_t pos = transcript.find(key); pos != std::string::npos;
       pos = transcript.find(key, pos + 1)) {
    total += std::stoul(transcript.substr(pos + key.size(), 12));
  }
  return total;
}

// The ServerMessages a WebSocket connection carried back, from a proxy
// transcript: the HTTP 101 head, then unmasked server frames. A message cut
// by a dropped connection is left out.
std::vector<proto::ServerMessage> WebSocketMessages(const std::string& t) {
  std::vector<proto::ServerMessage> out;
  size_t pos = t.find("\r\n\r\n");
  if (t.rfind("HTTP/1.1 101", 0) != 0 || pos == std::string::npos) return out;
  pos += 4;
  while (pos + 2 <= t.size()) {
    const uint8_t opcode = static_cast<uint8_t>(t[pos]) & 0x0f;
    uint64_t length = static_cast<uint8_t>(t[pos + 1]) & 0x7f;
    pos += 2;
    const int extra = length == 126 ? 2 : length == 127 ? 8 : 0;
    if (extra > 0) {
      if (pos + static_cast<size_t>(extra) > t.size()) break;
      length = 0;
      for (int i = 0; i < extra; ++i) {
        length =
            length << 8 | static_cast<uint8_t>(t[pos + static_cast<size_t>(i)]);
      }
      pos += static_cast<size_t>(extra);
    }
    if (pos + length > t.size()) break;
    if (opcode == 2) {
      proto::ServerMessage m;
      EXPECT_TRUE(m.ParseFromArray(t.data() + pos, static_cast<int>(length)));
      out.push_back(m);
    }
    pos += length;
  }
  return out;
}

// What a proxy saw the server send over WebSocket, every connection.
struct WebSocketTraffic {
  int headers = 0;                // StreamStart messages
  std::vector<uint32_t> cursors;  // of every packet, in order
  uint64_t header_and_payload_bytes = 0;
};

WebSocketTraffic Traffic(TcpProxy& proxy) {
  WebSocketTraffic traffic;
  for (const auto& t : proxy.Transcripts()) {
    for (const auto& m : WebSocketMessages(t)) {
      if (m.has_start()) {
        ++traffic.headers;
        traffic.header_and_payload_bytes += m.start().header().size();
      }
      if (m.has_packet()) {
        traffic.cursors.push_back(m.packet().cursor());
        traffic.header_and_payload_bytes += m.packet().payload().size();
      }
    }
  }
  return traffic;
}

class ClientE2eTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    catalog_ = *dir_ / "catalog";
    ASSERT_NO_FATAL_FAILURE(testing::CopySampleCatalog(
        catalog_, {testing::SampleMesh("holes.off"), testing::SampleMesh("elephant.off"),
                   testing::SampleMesh("textured/hue_ball.ply"),
                   testing::SampleMesh("textured/die.obj")}));
    std::filesystem::create_directories(*dir_ / "server");
    server_ = new ServerProcess(catalog_, *dir_ / "server");
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    const auto reply = HttpGet(server_->port(), "/v1/meshes");
    proto::MeshList list;
    google::protobuf::util::JsonParseOptions o;
    o.ignore_unknown_fields = true;
    ASSERT_TRUE(
        google::protobuf::util::JsonStringToMessage(reply.body, &list, o).ok());
    for (const auto& m : list.meshes()) {
      if (m.source().find("holes") != std::string::npos) holes_ = m.id();
      if (m.source().find("elephant") != std::string::npos) elephant_ = m.id();
      if (m.source().find("hue_ball") != std::string::npos) hue_ball_ = m.id();
      if (m.source().find("die.obj") != std::string::npos) die_ = m.id();
    }
    ASSERT_FALSE(holes_.empty()) << reply.body;
    ASSERT_FALSE(elephant_.empty()) << reply.body;
    ASSERT_FALSE(hue_ball_.empty()) << reply.body;
    ASSERT_FALSE(die_.empty()) << reply.body;
  }
  static void TearDownTestSuite() {
    delete server_;
    delete dir_;
  }

  static std::string Url(uint16_t port, const std::string& id) {
    return "http://127.0.0.1:" + std::to_string(port) + "/v1/meshes/" + id;
  }
  static std::string Url(const std::string& id) {
    return Url(server_->port(), id);
  }
  static std::string WsUrl(uint16_t port, const std::string& id) {
    return "ws://127.0.0.1:" + std::to_string(port) + "/v1/meshes/" + id;
  }
  static std::string WsUrl(const std::string& id) {
    return WsUrl(server_->port(), id);
  }

  // The mesh `meshwave decode` gives for the server's own truncation.
  std::string DecodeOfServerTruncation(const TempDir& dir,
                                       const std::string& id,
                                       const std::string& order,
                                       const std::string& query,
                                       const std::string& max_level = "") {
    const auto reply = HttpGet(
        server_->port(), "/v1/meshes/" + id + "/stream?order=" + order + query);
    EXPECT_EQ(reply.status, 200u) << reply.body;
    WriteFile(dir / "part.mwv", reply.body);
    std::vector<std::string> args = {"decode", (dir / "part.mwv").string(),
                                     (dir / "decoded.ply").string(), "--order",
                                     order};
    if (!max_level.empty()) {
      args.push_back("--max-level");
      args.push_back(max_level);
    }
    const auto r = RunCli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return ReadBytes(dir / "decoded.ply");
  }

  static inline TempDir* dir_ = nullptr;
  static inline std::filesystem::path catalog_;
  static inline ServerProcess* server_ = nullptr;
  static inline std::string holes_, elephant_, hue_ball_, die_;
};

TEST_F(ClientE2eTest, CatalogListsTheIngestedMeshes) {
  auto r = RunCli(
      {"catalog", "http://127.0.0.1:" + std::to_string(server_->port())});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(holes_), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(elephant_), std::string::npos) << r.out;
  r = RunCli({"catalog", "http://127.0.0.1:" + std::to_string(server_->port()),
              "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"meshes\""), std::string::npos);
}

TEST_F(ClientE2eTest, FetchAtABudgetEqualsDecodeOfTheSameTruncation) {
  TempDir dir;
  for (const std::string& id : {holes_, elephant_}) {
    for (const std::string order : {"quality", "resolution", "rd"}) {
      for (const std::string budget : {"2500", "6000"}) {
        const auto r = RunCli({"fetch", Url(id), "--budget", budget, "--order",
                               order, "--out", (dir / "fetched.ply").string()});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(ReadBytes(dir / "fetched.ply"),
                  DecodeOfServerTruncation(dir, id, order, "&budget=" + budget))
            << id << " " << order << " " << budget;
      }
    }
  }
}

// A stream with a colour channel (hue_ball.ply, ingested with its colours):
// fetch writes them as decode does, into a .glb (COLOR_0) or a .ply.
TEST_F(ClientE2eTest, FetchWritesTheColoursOfAColouredStream) {
  TempDir dir;
  const auto container = HttpGet(server_->port(), "/v1/meshes/" + hue_ball_ + "/container");
  ASSERT_EQ(container.status, 200u);
  WriteFile(dir / "whole.mwv", container.body);
  for (const std::string ext : {".glb", ".ply"}) {
    const auto fetched =
        RunCli({"fetch", Url(hue_ball_), "--out", (dir / ("fetched" + ext)).string()});
    ASSERT_EQ(fetched.exit_code, 0) << fetched.err;
    EXPECT_NE(fetched.out.find("with vertex colours"), std::string::npos) << fetched.out;
    const auto decoded = RunCli(
        {"decode", (dir / "whole.mwv").string(), (dir / ("decoded" + ext)).string()});
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    EXPECT_EQ(ReadBytes(dir / ("fetched" + ext)), ReadBytes(dir / ("decoded" + ext))) << ext;
  }
  auto asset = ReadMeshAsset(dir / "fetched.glb");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_FALSE(asset->color.empty());
}

// A textured stream (die.obj, baked at ingest): fetch says which texture
// level it holds — none at a budget that holds the geometry's first
// packets only, the finest for the whole stream — and writes the texture
// into the .glb.
TEST_F(ClientE2eTest, FetchSaysWhichTextureLevelItHolds) {
  TempDir dir;
  const auto head =
      RunCli({"fetch", Url(die_), "--budget", "1100", "--out", (dir / "head.glb").string()});
  ASSERT_EQ(head.exit_code, 0) << head.err;
  EXPECT_NE(head.out.find("texture not received yet"), std::string::npos) << head.out;
  const auto whole = RunCli({"fetch", Url(die_), "--out", (dir / "whole.glb").string()});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.out.find("textured: 256 x 224 (level 2 of 2)"), std::string::npos) << whole.out;
  auto asset = ReadMeshAsset(dir / "whole.glb");
  ASSERT_TRUE(asset.ok()) << asset.status().ToString();
  EXPECT_FALSE(asset->uv.empty());
  ASSERT_EQ(asset->images.size(), 1u);
  EXPECT_EQ(asset->images[0].width, 256u);
}

// Region requests on a textured stream: the texture levels are global
// (one image for the whole surface), so a region fetch gets them as any
// fetch does; refined to the end, the .glb equals the whole stream's.
TEST_F(ClientE2eTest, ARegionFetchOfATexturedStreamGetsItsTexture) {
  TempDir dir;
  const std::string state = (dir / "state.mwv").string();
  // Below the whole stream (14 KB), above the coarse level (WebP, 3.5 KB).
  const auto first = RunCli({"fetch", Url(die_), "--region", "0,0,0,0.5", "--budget", "8000",
                             "--out", (dir / "region.glb").string(), "--state", state});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("textured: 128 x 112 (level 1 of 2)"), std::string::npos)
      << first.out;
  const auto last = RunCli({"refine", state, "--region", "0,0,0,0.5", "--more", "1GiB", "--out",
                            (dir / "refined.glb").string()});
  ASSERT_EQ(last.exit_code, 0) << last.err;
  EXPECT_NE(last.out.find("textured: 256 x 224 (level 2 of 2)"), std::string::npos) << last.out;
  const auto whole = RunCli({"fetch", Url(die_), "--out", (dir / "whole.glb").string()});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(ReadBytes(dir / "refined.glb"), ReadBytes(dir / "whole.glb"));
}

TEST_F(ClientE2eTest, MaxLevelFetchEqualsDecodeWithTheSameLimit) {
  TempDir dir;
  const auto r =
      RunCli({"fetch", Url(elephant_), "--order", "resolution", "--max-level",
              "1", "--out", (dir / "coarse.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ParseReport(r.out);
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(ReadBytes(dir / "coarse.ply"),
            DecodeOfServerTruncation(dir, elephant_, "resolution",
                                     "&max_level=1", "1"));
}

TEST_F(ClientE2eTest, PsnrAndRateBudgets) {
  TempDir dir;
  auto r = RunCli({"fetch", Url(elephant_), "--psnr", "50", "--out",
                   (dir / "p.ply").string(), "--json", "--lods",
                   (dir / "lods").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto report = ParseReport(r.out);
  EXPECT_GE(report.estimated_psnr_db(), 50);
  ASSERT_GE(report.steps_size(), 2);
  // The step before the last had not reached it: the shortest prefix.
  EXPECT_LT(report.steps(report.steps_size() - 2).estimated_psnr_db(), 50);
  EXPECT_TRUE(std::filesystem::exists(report.steps(0).lod_file()));
  EXPECT_TRUE(std::filesystem::exists(
      report.steps(report.steps_size() - 1).lod_file()));

  // 400 kbit/s for 0.1 s is 5000 bytes.
  r = RunCli({"fetch", Url(elephant_), "--rate", "400kbit", "--deadline",
              "100ms", "--out", (dir / "rate.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(ParseReport(r.out).bytes(), 5000u);
  r = RunCli({"fetch", Url(elephant_), "--budget", "5000", "--out",
              (dir / "b.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadBytes(dir / "rate.ply"), ReadBytes(dir / "b.ply"));
}

TEST_F(ClientE2eTest, TruePsnrWithAReference) {
  TempDir dir;
  const auto r = RunCli({"fetch", Url(holes_), "--budget", "8000", "--out",
                         (dir / "h.ply").string(), "--json", "--reference",
                         testing::SampleMesh("holes.off").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ParseReport(r.out);
  EXPECT_GT(report.true_psnr_db(), 20);
  for (const auto& s : report.steps()) EXPECT_GT(s.true_psnr_db(), 0);
  // The "true" PSNR is the symmetric surface distance to the reference,
  // exactly what `meshwave compare REFERENCE DECODED` reports (up to the
  // float rounding of the written mesh), not a vertex-to-vertex match.
  const auto c = RunCli({"compare", testing::SampleMesh("holes.off").string(),
                         (dir / "h.ply").string(), "--json"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  proto::CompareReport compare;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(c.out, &compare).ok())
      << c.out;
  EXPECT_NEAR(report.true_psnr_db(), compare.surface().rms().psnr_db(), 0.01);
  EXPECT_NEAR(report.steps(report.steps_size() - 1).true_psnr_db(),
              report.true_psnr_db(), 1e-9);
}

TEST_F(ClientE2eTest, RefineTwiceEqualsOneLargerFetchAndNoPacketIsSentTwice) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  const std::string url = Url(proxy.port(), elephant_);
  const std::string state = (dir / "e.mwv").string();
  auto r = RunCli({"fetch", url, "--budget", "3000", "--order", "rd", "--state",
                   state, "--out", (dir / "first.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  size_t received = ParseReport(r.out).packets_received();
  for (const char* more : {"2000", "3000"}) {
    r = RunCli({"refine", state, "--more", more, "--out",
                (dir / "refined.ply").string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    received += ParseReport(r.out).packets_received();
  }
  const auto final_report = ParseReport(r.out);
  EXPECT_GT(final_report.packets_received(), 0u);
  EXPECT_EQ(received, final_report.packets());

  // Bit for bit: the state is the server's own container at the sum of the
  // budgets, and the mesh is a single fetch's.
  const auto whole = HttpGet(
      server_->port(), "/v1/meshes/" + elephant_ + "/stream?order=rd&budget=" +
                           std::to_string(3000 + 2000 + 3000));
  EXPECT_EQ(ReadBytes(state), whole.body);
  r = RunCli({"fetch", Url(elephant_), "--budget", "8000", "--order", "rd",
              "--out", (dir / "single.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadBytes(dir / "refined.ply"), ReadBytes(dir / "single.ply"));

  // What the server said it sent: every packet once.
  EXPECT_EQ(PacketsAnnounced(proxy.Transcript()), final_report.packets());
  // The state decodes with the plain decoder too.
  r = RunCli({"decode", state, (dir / "d.ply").string(), "--order", "rd"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(ClientE2eTest, RefuseACorruptStateFile) {
  TempDir dir;
  const std::string state = (dir / "s.mwv").string();
  auto r = RunCli({"fetch", Url(holes_), "--budget", "5000", "--state", state,
                   "--out", (dir / "a.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string bytes = ReadBytes(state);
  bytes[bytes.size() - 2] ^=
      0x55;  // inside the last payload: the CRC catches it
  WriteFile(state, bytes);
  r = RunCli({"refine", state, "--more", "4KiB"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("CRC-16 check mismatch"), std::string::npos) << r.err;
}

TEST_F(ClientE2eTest, ResumesAfterTheProxyCutsTheConnection) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  proxy.CutAfter(3000, 2);
  const auto r =
      RunCli({"fetch", Url(proxy.port(), elephant_), "--out",
              (dir / "cut.ply").string(), "--json", "--retry-delay", "20ms"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ParseReport(r.out);
  EXPECT_EQ(report.retries(), 2u);
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(report.packets_received(), report.packets());  // nothing twice
  EXPECT_EQ(ReadBytes(dir / "cut.ply"),
            DecodeOfServerTruncation(dir, elephant_, "quality", ""));
}

TEST_F(ClientE2eTest, ResumesWhenTheServerIsKilledMidStreamAndRestarted) {
  TempDir dir;
  std::filesystem::create_directories(dir / "a");
  std::filesystem::create_directories(dir / "b");
  auto first = std::make_unique<ServerProcess>(catalog_, dir / "a");
  ASSERT_TRUE(first->running());
  TcpProxy proxy(first->port());
  proxy.StallAfter(5000);
  testing::CliResult r;
  std::thread fetch([&] {
    r = RunCli({"fetch", Url(proxy.port(), elephant_), "--order", "rd", "--out",
                (dir / "k.ply").string(), "--json", "--retry-delay", "50ms"});
  });
  if (!proxy.WaitStalled(std::chrono::seconds(20))) {
    proxy.DropStalled();
    fetch.join();
    FAIL() << "the transfer never reached the stall point: " << r.err;
  }
  ::kill(first->pid(), SIGKILL);
  first->Stop();
  ServerProcess second(catalog_, dir / "b");
  ASSERT_TRUE(second.running());
  proxy.set_upstream(second.port());
  proxy.DropStalled();
  fetch.join();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ParseReport(r.out);
  EXPECT_GE(report.retries(), 1u);
  EXPECT_EQ(report.packets_received(), report.packets());
  EXPECT_EQ(ReadBytes(dir / "k.ply"),
            DecodeOfServerTruncation(dir, elephant_, "rd", ""));
}

TEST_F(ClientE2eTest, ReadTimeoutOnAStalledConnectionIsRetried) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  proxy.StallAfter(3000);  // never released
  const auto r = RunCli({"fetch", Url(proxy.port(), elephant_), "--out",
                         (dir / "t.ply").string(), "--json", "--timeout",
                         "300ms", "--retry-delay", "10ms"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ParseReport(r.out).retries(), 1u);
  proxy.DropStalled();
}

TEST_F(ClientE2eTest, ACorruptByteOnTheWireIsAClearError) {
  TempDir dir;
  TcpProxy clean(server_->port());
  auto r = RunCli({"fetch", Url(clean.port(), elephant_), "--budget", "6000",
                   "--out", (dir / "ok.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Find the first payload byte in what the server sent: after the HTTP
  // head, the preamble and the stream header.
  const std::string t = clean.Transcript();
  const size_t body = t.find("\r\n\r\n") + 4;
  uint32_t header = 0;
  for (int i = 7; i >= 4; --i)
    header = header << 8 | static_cast<uint8_t>(t[body + i]);
  TcpProxy corrupt(server_->port());
  corrupt.CorruptAt(static_cast<int64_t>(body + 8 + header + 100));
  r = RunCli({"fetch", Url(corrupt.port(), elephant_), "--budget", "6000",
              "--out", (dir / "bad.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("meshwave fetch: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("CRC-16 check mismatch"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.ply"));
  EXPECT_EQ(corrupt.connections(), 1);  // refused, not retried

  // A corrupt stream header is refused too.
  TcpProxy corrupt_header(server_->port());
  corrupt_header.CorruptAt(static_cast<int64_t>(body + 1));
  r = RunCli({"fetch", Url(corrupt_header.port(), elephant_), "--budget",
              "6000", "--out", (dir / "bad.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("wrong magic"), std::string::npos) << r.err;
}

TEST_F(ClientE2eTest, ServerRefusalsAreClearErrors) {
  TempDir dir;
  auto r =
      RunCli({"fetch", Url("0123456789ab"), "--out", (dir / "x.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("404"), std::string::npos) << r.err;
  r = RunCli({"fetch", Url(holes_), "--budget", "10", "--out",
              (dir / "x.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("smaller than the stream header"), std::string::npos)
      << r.err;
  r = RunCli({"fetch", "http://127.0.0.1:1/v1/meshes/0123456789ab", "--out",
              (dir / "x.ply").string(), "--retries", "1", "--retry-delay",
              "1ms"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("connecting to 127.0.0.1:1"), std::string::npos)
      << r.err;
  r = RunCli({"fetch", Url(holes_), "--budget", "1k", "--psnr", "40", "--out",
              (dir / "x.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
}

// The client's own limits (--max-header, --max-faces) refuse a stream
// before allocating for it, over both transports, and leave no output.
TEST_F(ClientE2eTest, ClientLimitsRefuseAnOversizeHeaderOrMesh) {
  TempDir dir;
  const auto out = dir / "x.ply";
  for (const std::string& url : {Url(elephant_), WsUrl(elephant_)}) {
    auto r =
        RunCli({"fetch", url, "--max-header", "100", "--out", out.string()});
    EXPECT_EQ(r.exit_code, 1) << url;
    EXPECT_NE(r.err.find("over this client's limit of 100"), std::string::npos)
        << r.err;
    r = RunCli({"fetch", url, "--max-faces", "100", "--out", out.string()});
    EXPECT_EQ(r.exit_code, 1) << url;
    EXPECT_NE(r.err.find("more than this decoder's limit of 100"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << url;
  }
  auto r = RunCli(
      {"fetch", Url(elephant_), "--max-header", "lots", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_FALSE(std::filesystem::exists(out));
}

// --- The same over WebSocket (GET /v1/ws) ---------------------------------

TEST_F(ClientE2eTest, WebSocketFetchAtABudgetEqualsDecodeOfTheSameTruncation) {
  TempDir dir;
  for (const std::string& id : {holes_, elephant_}) {
    for (const std::string order : {"quality", "resolution", "rd"}) {
      for (const std::string budget : {"2500", "6000"}) {
        const auto r =
            RunCli({"fetch", WsUrl(id), "--budget", budget, "--order", order,
                    "--out", (dir / "fetched.ply").string()});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(ReadBytes(dir / "fetched.ply"),
                  DecodeOfServerTruncation(dir, id, order, "&budget=" + budget))
            << id << " " << order << " " << budget;
      }
    }
  }
  // --ws turns an http URL into the WebSocket transport.
  TcpProxy proxy(server_->port());
  const auto r =
      RunCli({"fetch", Url(proxy.port(), elephant_), "--ws", "--budget", "6000",
              "--out", (dir / "flag.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Traffic(proxy).headers, 1);
  EXPECT_EQ(
      ReadBytes(dir / "flag.ply"),
      DecodeOfServerTruncation(dir, elephant_, "quality", "&budget=6000"));
}

TEST_F(ClientE2eTest, WebSocketMaxLevelAndPsnrFetchesEqualHttp) {
  TempDir dir;
  auto r =
      RunCli({"fetch", WsUrl(elephant_), "--order", "resolution", "--max-level",
              "1", "--out", (dir / "coarse.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(ParseReport(r.out).complete());
  EXPECT_EQ(ReadBytes(dir / "coarse.ply"),
            DecodeOfServerTruncation(dir, elephant_, "resolution",
                                     "&max_level=1", "1"));
  // A PSNR goal: the header alone first, then the packets by refine.
  r = RunCli({"fetch", WsUrl(elephant_), "--psnr", "50", "--order", "rd",
              "--out", (dir / "ws.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ws = ParseReport(r.out);
  r = RunCli({"fetch", Url(elephant_), "--psnr", "50", "--order", "rd", "--out",
              (dir / "http.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ws.packets(), ParseReport(r.out).packets());
  EXPECT_GE(ws.estimated_psnr_db(), 50);
  EXPECT_EQ(ReadBytes(dir / "ws.ply"), ReadBytes(dir / "http.ply"));
}

TEST_F(ClientE2eTest,
       WebSocketRefineTwiceEqualsOneLargerFetchAndNoByteIsSentTwice) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  const std::string state = (dir / "e.mwv").string();
  auto r = RunCli({"fetch", WsUrl(proxy.port(), elephant_), "--budget", "3000",
                   "--order", "rd", "--state", state, "--out",
                   (dir / "first.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The state remembers the ws:// URL: refine resumes over WebSocket.
  for (const char* more : {"2000", "3000"}) {
    r = RunCli({"refine", state, "--more", more, "--out",
                (dir / "refined.ply").string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto final_report = ParseReport(r.out);
  const auto whole =
      HttpGet(server_->port(),
              "/v1/meshes/" + elephant_ + "/stream?order=rd&budget=8000");
  EXPECT_EQ(ReadBytes(state), whole.body);
  r = RunCli({"fetch", Url(elephant_), "--budget", "8000", "--order", "rd",
              "--out", (dir / "single.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadBytes(dir / "refined.ply"), ReadBytes(dir / "single.ply"));

  // Counted on the wire: three connections, one header, every packet of
  // the final state exactly once and nothing else.
  const WebSocketTraffic traffic = Traffic(proxy);
  EXPECT_EQ(proxy.connections(), 3);
  EXPECT_EQ(traffic.headers, 1);
  ASSERT_EQ(traffic.cursors.size(), final_report.packets());
  for (size_t i = 0; i < traffic.cursors.size(); ++i) {
    EXPECT_EQ(traffic.cursors[i], i);
  }
  auto parsed = ParseContainer(whole.body);
  ASSERT_TRUE(parsed.ok());
  uint64_t payloads = 0;
  for (const auto& p : parsed->payloads) payloads += p.size();
  EXPECT_EQ(traffic.header_and_payload_bytes,
            parsed->header.bytes_without_present.size() + payloads);
}

TEST_F(ClientE2eTest, WebSocketSessionRefinesOnTheSameConnection) {
  TcpProxy proxy(server_->port());
  auto url = client::ParseMeshUrl(WsUrl(proxy.port(), elephant_));
  ASSERT_TRUE(url.ok());
  client::SessionOptions options;
  options.order = Progression::kRd;
  client::BlockingSession blocking(*url, options, client::TransportOptions{});
  ASSERT_TRUE(blocking.Fetch(client::Budget::Bytes(3000)).ok());
  const auto first = blocking.session().progress();
  const Status refined = blocking.Fetch(client::Budget::Bytes(8000));
  ASSERT_TRUE(refined.ok()) << refined.ToString();
  const auto p = blocking.session().progress();
  EXPECT_GT(p.packets, first.packets);
  EXPECT_EQ(proxy.connections(), 1);  // refine, not a new connection
  const auto whole =
      HttpGet(server_->port(),
              "/v1/meshes/" + elephant_ + "/stream?order=rd&budget=8000");
  EXPECT_EQ(blocking.session().Container(), whole.body);
  // Bytes received: the header (without `present`) and each payload once.
  const WebSocketTraffic traffic = Traffic(proxy);
  EXPECT_EQ(traffic.headers, 1);
  EXPECT_EQ(traffic.cursors.size(), p.packets);
  EXPECT_EQ(p.received_bytes, traffic.header_and_payload_bytes);
  EXPECT_EQ(p.packets_received, p.packets);
}

TEST_F(ClientE2eTest, WebSocketResumesAfterTheProxyCutsTheConnection) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  proxy.CutAfter(3000, 2);
  const auto r =
      RunCli({"fetch", WsUrl(proxy.port(), elephant_), "--out",
              (dir / "cut.ply").string(), "--json", "--retry-delay", "20ms"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ParseReport(r.out);
  EXPECT_EQ(report.retries(), 2u);
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(report.packets_received(), report.packets());  // nothing twice
  EXPECT_EQ(proxy.connections(), 3);
  // Whole packets on the wire: each cursor once (a packet cut in half is
  // not counted), the header once.
  const WebSocketTraffic traffic = Traffic(proxy);
  EXPECT_EQ(traffic.headers, 1);
  EXPECT_EQ(traffic.cursors.size(), report.packets());
  EXPECT_EQ(ReadBytes(dir / "cut.ply"),
            DecodeOfServerTruncation(dir, elephant_, "quality", ""));
}

TEST_F(ClientE2eTest, WebSocketReadTimeoutOnAStalledConnectionIsRetried) {
  TempDir dir;
  TcpProxy proxy(server_->port());
  proxy.StallAfter(3000);  // never released
  const auto r = RunCli({"fetch", WsUrl(proxy.port(), elephant_), "--out",
                         (dir / "t.ply").string(), "--json", "--timeout",
                         "300ms", "--retry-delay", "10ms"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ParseReport(r.out).retries(), 1u);
  EXPECT_EQ(ReadBytes(dir / "t.ply"),
            DecodeOfServerTruncation(dir, elephant_, "quality", ""));
  proxy.DropStalled();
}

TEST_F(ClientE2eTest, WebSocketPacedFetch) {
  TempDir dir;
  // 10838 bytes at 64 kbit/s (8000 B/s): over a second, well under two.
  const auto start = std::chrono::steady_clock::now();
  const auto r = RunCli({"fetch", WsUrl(elephant_), "--pace", "64kbit", "--out",
                         (dir / "paced.ply").string()});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(seconds, 1.0);
  EXPECT_EQ(ReadBytes(dir / "paced.ply"),
            DecodeOfServerTruncation(dir, elephant_, "quality", ""));
}

TEST_F(ClientE2eTest, WebSocketServerRefusalsAreClearErrors) {
  TempDir dir;
  auto r = RunCli(
      {"fetch", WsUrl("0123456789ab"), "--out", (dir / "x.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no mesh with id 0123456789ab"), std::string::npos)
      << r.err;
  r = RunCli({"fetch", WsUrl(holes_), "--budget", "10", "--out",
              (dir / "x.ply").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("smaller than the stream header"), std::string::npos)
      << r.err;
  r = RunCli({"fetch", "ws://127.0.0.1:1/v1/meshes/0123456789ab", "--out",
              (dir / "x.ply").string(), "--retries", "1", "--retry-delay",
              "1ms"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("connecting to 127.0.0.1:1"), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace meshwave
