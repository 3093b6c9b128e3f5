// The viewer's static files served by the meshwave-server binary under
// /viewer/ (server/viewer_files.*): Content-Type by extension, ETag and
// Cache-Control with 304 revalidation, HEAD, 404 for what is missing,
// traversal refused (.., encoded dots and slashes, a symlink leading out),
// GET/HEAD only; --viewer-dir, the config field and the default (the build
// tree's copy of web/viewer).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_data.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "server_process_testonly.h"

namespace meshwave::testing {
namespace {

void WriteFile(const std::filesystem::path& path, const std::string& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

bool IsJsonError(const HttpReply& r) {
  return r.Header("content-type") == "application/json" &&
         r.body.find("\"error\"") != std::string::npos;
}

class ServerViewerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    viewer_ = tmp_ / "viewer";
    WriteFile(viewer_ / "index.html",
              "<!doctype html><title>test viewer</title>\n");
    WriteFile(viewer_ / "app.js", "export const x = 1;\n");
    WriteFile(viewer_ / "style.css", "body { margin: 0; }\n");
    WriteFile(viewer_ / "decoder.wasm", std::string("\0asm\1\0\0\0", 8));
    WriteFile(viewer_ / "data.bin", "raw");
    WriteFile(viewer_ / "sub" / "deep.js", "// deep\n");
    WriteFile(tmp_ / "secret.txt", "outside the viewer");
    std::filesystem::create_symlink(tmp_ / "secret.txt", viewer_ / "link.txt");
    std::filesystem::create_directories(tmp_ / "work");
    server_ = std::make_unique<ServerProcess>(
        tmp_ / "catalog", tmp_ / "work", std::vector<std::string>{},
        std::vector<std::string>{"--viewer-dir", viewer_.string()});
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    port_ = server_->port();
  }

  void TearDown() override {
    if (server_) {
      EXPECT_EQ(server_->Stop(), 0) << ReadBytes(server_->log());
    }
  }

  TempDir tmp_;
  std::filesystem::path viewer_;
  std::unique_ptr<ServerProcess> server_;
  uint16_t port_ = 0;
};

TEST_F(ServerViewerTest, ServesFilesWithTheirContentType) {
  const struct {
    const char* target;
    const char* type;
    std::string body;
  } cases[] = {
      {"/viewer/", "text/html; charset=utf-8",
       ReadBytes(viewer_ / "index.html")},
      {"/viewer/index.html", "text/html; charset=utf-8",
       ReadBytes(viewer_ / "index.html")},
      {"/viewer/app.js", "text/javascript; charset=utf-8",
       "export const x = 1;\n"},
      {"/viewer/style.css", "text/css; charset=utf-8", "body { margin: 0; }\n"},
      {"/viewer/decoder.wasm", "application/wasm",
       std::string("\0asm\1\0\0\0", 8)},
      {"/viewer/data.bin", "application/octet-stream", "raw"},
      {"/viewer/sub/deep.js", "text/javascript; charset=utf-8", "// deep\n"},
      {"/viewer/app.js?v=2", "text/javascript; charset=utf-8",
       "export const x = 1;\n"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.target);
    const HttpReply r = HttpGet(port_, c.target);
    EXPECT_EQ(r.status, 200u);
    EXPECT_EQ(r.Header("content-type"), c.type);
    EXPECT_EQ(r.body, c.body);
    EXPECT_EQ(r.Header("x-content-type-options"), "nosniff");
  }
}

TEST_F(ServerViewerTest, RedirectsTheBareDirectory) {
  const HttpReply r = HttpGet(port_, "/viewer");
  EXPECT_EQ(r.status, 301u);
  EXPECT_EQ(r.Header("location"), "/viewer/");
}

TEST_F(ServerViewerTest, IsCacheableAndRevalidatedWithTheEtag) {
  const HttpReply first = HttpGet(port_, "/viewer/app.js");
  const std::string etag = first.Header("etag");
  ASSERT_EQ(etag.size(), 66u) << etag;  // "<sha256 hex>"
  EXPECT_EQ(first.Header("cache-control"), "no-cache");
  const HttpReply again =
      HttpGet(port_, "/viewer/app.js", {{"If-None-Match", etag}});
  EXPECT_EQ(again.status, 304u);
  EXPECT_TRUE(again.body.empty());
  EXPECT_EQ(again.Header("etag"), etag);
  EXPECT_EQ(
      HttpGet(port_, "/viewer/app.js", {{"If-None-Match", "W/" + etag}}).status,
      304u);
  EXPECT_EQ(
      HttpGet(port_, "/viewer/app.js", {{"If-None-Match", "\"other\""}}).status,
      200u);
  // A changed file gets a new tag: a browser never keeps a stale page.
  WriteFile(viewer_ / "app.js", "export const x = 2;\n");
  const HttpReply changed =
      HttpGet(port_, "/viewer/app.js", {{"If-None-Match", etag}});
  EXPECT_EQ(changed.status, 200u);
  EXPECT_EQ(changed.body, "export const x = 2;\n");
  EXPECT_NE(changed.Header("etag"), etag);
}

TEST_F(ServerViewerTest, AnswersHeadWithoutABody) {
  HttpConnection c(port_);
  const HttpReply r = c.Send(http::verb::head, "/viewer/style.css");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.Header("content-type"), "text/css; charset=utf-8");
  EXPECT_EQ(r.Header("content-length"), "20");
  EXPECT_TRUE(r.body.empty());
}

TEST_F(ServerViewerTest, MissingFilesAre404) {
  for (const char* target :
       {"/viewer/nothing.js", "/viewer/sub", "/viewer/sub/none/x.js",
        "/viewerx", "/viewer/index.html/x"}) {
    SCOPED_TRACE(target);
    const HttpReply r = HttpGet(port_, target);
    EXPECT_EQ(r.status, 404u);
    EXPECT_TRUE(IsJsonError(r)) << r.body;
  }
}

TEST_F(ServerViewerTest, RefusesTraversal) {
  // Malformed targets: 400 from the request-target parser.
  for (const char* target :
       {"/viewer/../secret.txt", "/viewer/%2e%2e/secret.txt",
        "/viewer/sub/..%2f..%2fsecret.txt", "/viewer/sub%5c..%5csecret.txt",
        "/viewer/./app.js", "/viewer//app.js", "/viewer/sub/"}) {
    SCOPED_TRACE(target);
    const HttpReply r = HttpGet(port_, target);
    EXPECT_EQ(r.status, 400u);
    EXPECT_TRUE(IsJsonError(r)) << r.body;
    EXPECT_EQ(r.body.find("outside the viewer"), std::string::npos);
  }
  // A symlink leading out of the directory: as if it were not there.
  const HttpReply link = HttpGet(port_, "/viewer/link.txt");
  EXPECT_EQ(link.status, 404u);
  EXPECT_EQ(link.body.find("outside the viewer"), std::string::npos);
}

TEST_F(ServerViewerTest, OnlyGetAndHead) {
  HttpConnection c(port_);
  const HttpReply r = c.Send(http::verb::delete_, "/viewer/app.js");
  EXPECT_EQ(r.status, 405u);
  EXPECT_EQ(r.Header("allow"), "GET, HEAD");
}

// Without --viewer-dir: the build tree's copy of web/viewer (the
// meshwave_viewer target, a dependency of meshwave-server), here the real
// page and the vendored three.js.
TEST(ServerViewerDefaultTest, ServesTheBuildTreesViewer) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "work");
  ServerProcess server(tmp / "catalog", tmp / "work");
  ASSERT_TRUE(server.running()) << ReadBytes(server.log());
  const std::filesystem::path source =
      SampleDataDir().parent_path() / "web" /
      "viewer";
  const HttpReply index = HttpGet(server.port(), "/viewer/");
  EXPECT_EQ(index.status, 200u);
  EXPECT_EQ(index.body, ReadBytes(source / "index.html"));
  const HttpReply three =
      HttpGet(server.port(), "/viewer/vendor/three/three.module.js");
  EXPECT_EQ(three.status, 200u);
  EXPECT_EQ(three.Header("content-type"), "text/javascript; charset=utf-8");
  EXPECT_EQ(three.body,
            ReadBytes(source / "vendor" / "three" / "three.module.js"));
  EXPECT_EQ(server.Stop(), 0);
}

// The config file's viewer_dir, and a directory that does not exist.
TEST(ServerViewerDefaultTest,
     TakesTheConfigFieldAndSaysWhenTheViewerIsMissing) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "work");
  WriteFile(tmp / "mine" / "index.html", "mine");
  WriteFile(tmp / "server.conf",
            "viewer_dir: \"" + (tmp / "mine").string() + "\"\n");
  {
    ServerProcess server(tmp / "catalog", tmp / "work", {},
                         {"--config", (tmp / "server.conf").string()});
    ASSERT_TRUE(server.running()) << ReadBytes(server.log());
    EXPECT_EQ(HttpGet(server.port(), "/viewer/").body, "mine");
    EXPECT_EQ(server.Stop(), 0);
  }
  ServerProcess server(tmp / "catalog", tmp / "work", {},
                       {"--viewer-dir", (tmp / "absent").string()});
  ASSERT_TRUE(server.running()) << ReadBytes(server.log());
  const HttpReply r = HttpGet(server.port(), "/viewer/");
  EXPECT_EQ(r.status, 404u);
  EXPECT_NE(r.body.find("--viewer-dir"), std::string::npos) << r.body;
  EXPECT_EQ(server.Stop(), 0);
}

}  // namespace
}  // namespace meshwave::testing
