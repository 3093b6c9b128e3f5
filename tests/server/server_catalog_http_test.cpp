// The requests of the HTTP API that change the catalog, end to end against
// the real meshwave-server: uploads and deletes (the token, the same bytes
// twice, a fidelity asked for) and a container on disk of another format
// version.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "catalog.h"
#include "meshwave/container.h"
#include "meshwave/mesh_io.h"
#include "meshwave/metrics.h"
#include "meshwave/progressive_decoder.h"
#include "server_http_fixture_testonly.h"
#include "sha256.h"
#include "stream.pb.h"
#include "stream/stream_format.h"

namespace meshwave::testing {
namespace {

using server::Sha256Hex;

TEST_F(ServerHttpTest, UploadAndDeleteNeedTheToken) {
  const std::string mesh = ReadBytes(SampleMesh("holes.off"));
  HttpConnection c1(port_);
  HttpReply r = c1.Send(http::verb::post, "/v1/meshes?name=uploaded", {}, mesh);
  EXPECT_EQ(r.status, 401u);
  EXPECT_TRUE(IsJsonError(r));
  HttpConnection c2(port_);
  r = c2.Send(http::verb::post, "/v1/meshes?name=uploaded", {{"Authorization", "Bearer wrong"}},
              mesh);
  EXPECT_EQ(r.status, 403u);
  HttpConnection c3(port_);
  const std::pair<std::string, std::string> auth = {"Authorization", std::string("Bearer ") + kToken};
  r = c3.Send(http::verb::post, "/v1/meshes?name=uploaded", {auth}, mesh);
  ASSERT_EQ(r.status, 201u) << r.body;
  proto::MeshSummary summary;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &summary).ok());
  EXPECT_EQ(summary.name(), "uploaded");
  EXPECT_EQ(r.Header("location"), "/v1/meshes/" + summary.id());
  r = c3.Send(http::verb::post, "/v1/meshes?name=uploaded", {auth}, mesh);
  EXPECT_EQ(r.status, 200u);  // same bytes: the same entry
  EXPECT_EQ(ParseList(HttpGet(port_, "/v1/meshes").body).total(), 5u);
  r = c3.Send(http::verb::post, "/v1/meshes?name=junk&format=ply", {auth}, "ply\nnonsense\n");
  EXPECT_EQ(r.status, 422u);
  EXPECT_TRUE(IsJsonError(r));

  const std::string target = "/v1/meshes/" + summary.id();
  EXPECT_EQ(HttpConnection(port_).Send(http::verb::delete_, target).status, 401u);
  EXPECT_EQ(HttpConnection(port_)
                .Send(http::verb::delete_, target, {{"Authorization", "Bearer nope"}})
                .status,
            403u);
  EXPECT_EQ(HttpConnection(port_).Send(http::verb::delete_, target, {auth}).status, 204u);
  EXPECT_EQ(HttpGet(port_, target).status, 404u);
  EXPECT_EQ(HttpGet(port_, target + "/container").status, 404u);
  EXPECT_EQ(HttpConnection(port_).Send(http::verb::delete_, target, {auth}).status, 404u);
  EXPECT_EQ(ParseList(HttpGet(port_, "/v1/meshes").body).total(), 4u);
}

// POST ?fidelity=DB: the upload is remeshed denser until the complete
// stream reaches DB against it, measured here on the served container
// against the uploaded file; a fidelity out of range is a 400.
TEST_F(ServerHttpTest, UploadWithAFidelityReachesItAgainstTheUpload) {
  const std::pair<std::string, std::string> auth = {"Authorization", std::string("Bearer ") + kToken};
  const std::string mesh = ReadBytes(SampleMesh("elephant.off"));
  for (const char* bad : {"151", "abc", "-3"}) {
    HttpReply r = HttpConnection(port_).Send(
        http::verb::post, std::string("/v1/meshes?name=e&format=off&fidelity=") + bad, {auth}, mesh);
    EXPECT_EQ(r.status, 400u) << bad << ": " << r.body;
    EXPECT_TRUE(IsJsonError(r)) << bad;
  }
  // fidelity=0: one remesh at about the sample's density, about 60 dB
  // against it; the densest an upload may ask for (4 times its vertices)
  // reaches about 70.
  HttpReply r = HttpConnection(port_).Send(
      http::verb::post, "/v1/meshes?name=plain&format=off&fidelity=0", {auth}, mesh);
  ASSERT_EQ(r.status, 201u) << r.body;
  proto::MeshSummary plain;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &plain).ok());
  constexpr double kAsked = 65;
  r = HttpConnection(port_).Send(
      http::verb::post, "/v1/meshes?name=fine&format=off&fidelity=65", {auth}, mesh);
  ASSERT_EQ(r.status, 201u) << r.body;
  proto::MeshSummary fine;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &fine).ok());
  EXPECT_GT(fine.vertices(), plain.vertices());

  const std::string container = HttpGet(port_, "/v1/meshes/" + fine.id() + "/container").body;
  auto parsed = ParseContainer(container);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  auto decoder = ProgressiveDecoder::Create(parsed->header);
  ASSERT_TRUE(decoder.ok());
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    ASSERT_TRUE((*decoder)->AddPacket(parsed->ids[i], parsed->payloads[i]).ok());
  }
  auto original = ReadMesh(SampleMesh("elephant.off"));
  ASSERT_TRUE(original.ok());
  auto d = SymmetricSurfaceDistance(*original, (*decoder)->Mesh());
  ASSERT_TRUE(d.ok());
  EXPECT_GE(d->PsnrDb(d->rms), kAsked);
  EXPECT_EQ(HttpConnection(port_).Send(http::verb::delete_, "/v1/meshes/" + fine.id(), {auth}).status,
            204u);
}

// A container of a format version this build no longer reads (older than
// the previous one, docs/DEPLOY.md "Upgrades"): the row and the file are
// intact, but this build cannot read them. That is the server's condition, not the
// client's: 500, naming both versions, and the other meshes still served.
TEST_F(ServerHttpTest, AContainerOfAnotherFormatVersionAnswers500NamingBothVersions) {
  const std::string id = ids_.at("holes_copy");
  auto catalog = server::Catalog::Open(catalog_.string());
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  auto found = (*catalog)->Find(id);
  ASSERT_TRUE(found.ok() && *found);
  server::CatalogEntry entry = **found;
  const auto path = (*catalog)->ContainerPath(entry);
  const std::string original = ReadBytes(path);  // the views below point into it
  auto parsed = ParseContainer(original);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  proto::StreamHeader header;
  ASSERT_TRUE(header.ParseFromString(parsed->header.bytes_without_present));
  const uint32_t older = kOldestReadFormatVersion - 1;
  header.set_format_version(older);
  std::string bytes = SerializeContainerHead(header.SerializeAsString(), parsed->ids);
  for (std::string_view payload : parsed->payloads) bytes += payload;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  ASSERT_TRUE((*catalog)->Remove(id).ok());
  entry.sha256 = Sha256Hex(bytes);
  ASSERT_TRUE((*catalog)->Insert(entry).ok());

  for (const std::string& target : {"/v1/meshes/" + id + "/stream?budget=5000",
                                    "/v1/meshes/" + id + "/container"}) {
    const HttpReply r = HttpGet(port_, target);
    EXPECT_EQ(r.status, 500u) << target;
    EXPECT_TRUE(IsJsonError(r)) << r.body;
    EXPECT_NE(r.body.find("format version " + std::to_string(older) +
                          " (this build reads versions " +
                          std::to_string(kOldestReadFormatVersion) + " to " +
                          std::to_string(kFormatVersion) + ")"),
              std::string::npos)
        << r.body;
  }
  EXPECT_EQ(HttpGet(port_, "/v1/meshes/" + ids_.at("holes") + "/stream?budget=5000").status,
            200u);
}

// The originals: what was uploaded comes back byte for byte to the holder
// of the upload token, to nobody else, and no shared cache may keep it.
TEST_F(ServerHttpTest, OriginalsGoToTheTokenHolderOnly) {
  const std::pair<std::string, std::string> auth = {"Authorization", std::string("Bearer ") + kToken};
  const std::string mesh = ReadBytes(SampleMesh("holes.off"));
  HttpReply r = HttpConnection(port_).Send(http::verb::post, "/v1/meshes?name=mine", {auth}, mesh);
  ASSERT_EQ(r.status, 201u) << r.body;
  proto::MeshSummary summary;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &summary).ok());
  EXPECT_TRUE(summary.has_original());
  const std::string base = "/v1/meshes/" + summary.id() + "/original";

  EXPECT_EQ(HttpGet(port_, base).status, 401u);
  EXPECT_EQ(HttpGet(port_, base + "/mine.off").status, 401u);
  EXPECT_EQ(HttpGet(port_, base, {{"Authorization", "Bearer nope"}}).status, 403u);
  r = HttpGet(port_, base, {auth});
  ASSERT_EQ(r.status, 200u) << r.body;
  EXPECT_EQ(r.Header("cache-control"), "private, no-store");
  proto::OriginalInfo info;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &info).ok()) << r.body;
  EXPECT_EQ(info.mesh_id(), summary.id());
  EXPECT_EQ(info.main(), "mine.off");
  EXPECT_EQ(info.format(), "off");
  ASSERT_EQ(info.files_size(), 1);
  EXPECT_EQ(info.files(0).sha256(), Sha256Hex(mesh));
  EXPECT_EQ(info.files(0).bytes(), mesh.size());
  r = HttpGet(port_, base + "/mine.off", {auth});
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, mesh);
  EXPECT_EQ(r.Header("cache-control"), "private, no-store");
  EXPECT_EQ(HttpGet(port_, base + "/other.off", {auth}).status, 404u);
  // The catalog's own entries, ingested from files, kept theirs too.
  r = HttpGet(port_, "/v1/meshes/" + ids_.at("holes") + "/original/holes.off", {auth});
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, mesh);
}

// An upload larger than upload_limit_bytes is refused from its declared
// length, before its body is sent, with a message naming the limit.
TEST_F(ServerHttpTest, AnUploadOverTheLimitIsRefusedBeforeItIsRead) {
  HttpConnection c(port_);
  const HttpReply r = c.SendRaw(std::string("POST /v1/meshes?name=big HTTP/1.1\r\nHost: x\r\n") +
                                "Authorization: Bearer " + kToken +
                                "\r\nContent-Length: 1000000000\r\nExpect: 100-continue\r\n\r\n");
  EXPECT_EQ(r.status, 413u);
  EXPECT_TRUE(IsJsonError(r));
  EXPECT_NE(r.body.find("1000000000 bytes, more than this server's limit of 67108864 bytes "
                        "(upload_limit_bytes)"),
            std::string::npos)
      << r.body;
  EXPECT_EQ(ParseList(HttpGet(port_, "/v1/meshes").body).total(), 4u);
}

}  // namespace
}  // namespace meshwave::testing
