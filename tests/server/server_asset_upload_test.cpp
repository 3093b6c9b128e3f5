// Uploads of assets, end to end against the real meshwave-server (and its
// upload worker): a coloured PLY is served with its colour channel, a .glb
// body is read as glTF, an OBJ with its material library and texture comes
// as a multipart/form-data body and is kept whole as the original, and each
// malformed multipart body is refused with its own message, storing nothing.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/stream_header.h"
#include "server_http_fixture_testonly.h"
#include "sha256.h"

namespace meshwave::testing {
namespace {

const std::pair<std::string, std::string> Auth() {
  return {"Authorization", std::string("Bearer ") + kToken};
}

struct FilePart {
  std::string filename, content;
};

constexpr char kBoundary[] = "----meshwave-test-7d3f";

std::pair<std::string, std::string> MultipartType() {
  return {"Content-Type", std::string("multipart/form-data; boundary=") + kBoundary};
}

// A body as `curl -F f=@file` sends it.
std::string Multipart(const std::vector<FilePart>& parts) {
  std::string body;
  size_t i = 0;
  for (const FilePart& p : parts) {
    body += std::string("--") + kBoundary + "\r\nContent-Disposition: form-data; name=\"f" +
            std::to_string(i++) + "\"; filename=\"" + p.filename +
            "\"\r\nContent-Type: application/octet-stream\r\n\r\n" + p.content + "\r\n";
  }
  return body + "--" + kBoundary + "--\r\n";
}

proto::MeshSummary Summary(const HttpReply& r) {
  proto::MeshSummary summary;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &summary).ok()) << r.body;
  return summary;
}

// The header of the container the server serves for `id`.
StreamHeader ServedHeader(uint16_t port, const std::string& id) {
  const std::string container = HttpGet(port, "/v1/meshes/" + id + "/container").body;
  auto parsed = ParseContainer(container);
  EXPECT_TRUE(parsed.ok()) << parsed.status().ToString();
  return parsed.ok() ? parsed->header : StreamHeader{};
}

// Its colour channels.
size_t ServedChannels(uint16_t port, const std::string& id) {
  return ServedHeader(port, id).channels.size();
}

TEST_F(ServerHttpTest, AColouredPlyIsServedWithItsColourChannel) {
  const std::string ply = ReadBytes(SampleMesh("textured/hue_ball.ply"));
  HttpReply r = HttpConnection(port_).Send(http::verb::post, "/v1/meshes?name=ball", {Auth()}, ply);
  ASSERT_EQ(r.status, 201u) << r.body;
  EXPECT_EQ(ServedChannels(port_, Summary(r).id()), 1u);
  // A geometry-only sample has none.
  EXPECT_EQ(ServedChannels(port_, ids_.at("holes")), 0u);
}

TEST_F(ServerHttpTest, AGlbBodyIsReadAsGltfSniffedOrNamed) {
  const std::string glb = ReadBytes(SampleMesh("textured/ring.glb"));
  HttpReply r = HttpConnection(port_).Send(http::verb::post, "/v1/meshes?name=ring", {Auth()}, glb);
  ASSERT_EQ(r.status, 201u) << r.body;
  const proto::MeshSummary sniffed = Summary(r);
  EXPECT_EQ(sniffed.source(), "ring.glb");
  // Its texture, two materials and COLOR_0 are baked into maps: a texture
  // and no colour channel.
  const StreamHeader header = ServedHeader(port_, sniffed.id());
  ASSERT_TRUE(header.texture.has_value());
  EXPECT_GE(header.texture->maps.size(), 1u);
  EXPECT_TRUE(header.channels.empty());
  r = HttpConnection(port_).Send(http::verb::post, "/v1/meshes?name=ring&format=glb", {Auth()},
                                 glb);
  EXPECT_EQ(r.status, 200u) << r.body;  // the same file, name and settings
  EXPECT_EQ(Summary(r).id(), sniffed.id());
}

TEST_F(ServerHttpTest, AMultipartUploadKeepsEveryFileOfTheAsset) {
  const std::vector<FilePart> files = {
      {"die.obj", ReadBytes(SampleMesh("textured/die.obj"))},
      {"die.mtl", ReadBytes(SampleMesh("textured/die.mtl"))},
      {"die.png", ReadBytes(SampleMesh("textured/die.png"))}};
  HttpReply r = HttpConnection(port_).Send(http::verb::post, "/v1/meshes?name=die",
                                           {Auth(), MultipartType()}, Multipart(files));
  ASSERT_EQ(r.status, 201u) << r.body;
  const proto::MeshSummary summary = Summary(r);
  EXPECT_EQ(summary.source(), "die.obj");
  r = HttpGet(port_, "/v1/meshes/" + summary.id() + "/original", {Auth()});
  ASSERT_EQ(r.status, 200u) << r.body;
  proto::OriginalInfo info;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &info).ok()) << r.body;
  EXPECT_EQ(info.main(), "die.obj");
  ASSERT_EQ(info.files_size(), 3);
  for (const FilePart& f : files) {
    bool found = false;
    for (const auto& kept : info.files()) {
      if (kept.name() != f.filename) continue;
      found = true;
      EXPECT_EQ(kept.sha256(), server::Sha256Hex(f.content)) << f.filename;
    }
    EXPECT_TRUE(found) << f.filename;
    EXPECT_EQ(HttpGet(port_, "/v1/meshes/" + summary.id() + "/original/" + f.filename, {Auth()})
                  .body,
              f.content);
  }
}

// One .obj alone cannot bring its material library: its geometry is
// stored (sent as parts without the .mtl, the same file is refused).
TEST_F(ServerHttpTest, ASingleObjBodyNamingAMaterialLibraryKeepsItsGeometry) {
  const HttpReply r = HttpConnection(port_).Send(http::verb::post,
                                                 "/v1/meshes?name=lone_die&format=obj", {Auth()},
                                                 ReadBytes(SampleMesh("textured/die.obj")));
  ASSERT_EQ(r.status, 201u) << r.body;
  EXPECT_EQ(Summary(r).vertices(), 866u);
}

TEST_F(ServerHttpTest, BadMultipartUploadsAreRefusedSayingWhyAndStoreNothing) {
  const std::string off = ReadBytes(SampleMesh("holes.off"));
  const std::string good = Multipart({{"a.off", off}});
  struct Case {
    std::string query, body;
    unsigned status;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"", Multipart({{"a.mtl", "newmtl x\n"}}), 422, "no part is a mesh file"},
      {"", Multipart({{"a.off", off}, {"b.ply", "ply"}}), 400, "say which one to read with main="},
      {"", Multipart({{"a.off", off}, {"a.off", off}}), 400, "two parts are named 'a.off'"},
      {"", Multipart({{"../a.off", off}}), 400, "segment"},
      {"", good.substr(0, good.size() / 2), 400, "truncated"},
      {"", "--" + std::string(kBoundary) + "\r\nX: y\r\n\r\nz\r\n--" + kBoundary + "--", 400,
       "no Content-Disposition"},
      {"&main=b.off", good, 400, "names none of the parts"},
      {"&format=off", good, 400, "format= is for a single-file body"},
      // An asset whose texture is missing: refused, not stored without it.
      {"", Multipart({{"die.obj", ReadBytes(SampleMesh("textured/die.obj"))},
                      {"die.mtl", ReadBytes(SampleMesh("textured/die.mtl"))}}),
       422, "texture die.png is missing"},
  };
  const auto blobs = [&] {
    size_t n = 0;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(catalog_ / "originals", ec), end; !ec && it != end;
         it.increment(ec)) {
      ++n;
    }
    return n;
  };
  const size_t before = ParseList(HttpGet(port_, "/v1/meshes").body).total();
  const size_t blobs_before = blobs();
  ASSERT_GT(blobs_before, 0u);
  for (const Case& c : cases) {
    const HttpReply r = HttpConnection(port_).Send(
        http::verb::post, "/v1/meshes?name=bad" + c.query, {Auth(), MultipartType()}, c.body);
    EXPECT_EQ(r.status, c.status) << c.message << ": " << r.body;
    EXPECT_TRUE(IsJsonError(r)) << r.body;
    EXPECT_NE(r.body.find(c.message), std::string::npos) << r.body;
  }
  // A multipart Content-Type without a boundary.
  const HttpReply r = HttpConnection(port_).Send(
      http::verb::post, "/v1/meshes?name=bad", {Auth(), {"Content-Type", "multipart/form-data"}},
      good);
  EXPECT_EQ(r.status, 400u) << r.body;
  EXPECT_EQ(ParseList(HttpGet(port_, "/v1/meshes").body).total(), before);
  EXPECT_EQ(blobs(), blobs_before);
}

}  // namespace
}  // namespace meshwave::testing
