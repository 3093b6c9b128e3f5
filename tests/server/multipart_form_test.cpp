// The multipart/form-data parser (untrusted upload bodies) and the choice
// of an upload's files and main file from its parts.
#include "multipart_form.h"

#include <gtest/gtest.h>

#include <string>

#include "upload_files.h"

namespace meshwave::server {
namespace {

// A body as curl -F sends it: one part per (field, filename, content).
struct Part {
  std::string field, filename, content;
};
std::string Body(const std::vector<Part>& parts, const std::string& boundary = "XyZ-12") {
  std::string body;
  for (const Part& p : parts) {
    body += "--" + boundary + "\r\nContent-Disposition: form-data; name=\"" + p.field + "\"";
    if (!p.filename.empty()) body += "; filename=\"" + p.filename + "\"";
    body += "\r\nContent-Type: application/octet-stream\r\n\r\n" + p.content + "\r\n";
  }
  return body + "--" + boundary + "--\r\n";
}

TEST(MultipartFormTest, ReadsTheBoundaryOfAContentType) {
  EXPECT_TRUE(IsMultipartFormData("multipart/form-data; boundary=abc"));
  EXPECT_TRUE(IsMultipartFormData("Multipart/Form-Data;boundary=abc"));
  EXPECT_FALSE(IsMultipartFormData("application/octet-stream"));
  EXPECT_FALSE(IsMultipartFormData("multipart/mixed; boundary=abc"));
  EXPECT_EQ(*MultipartBoundary("multipart/form-data; boundary=----abc123"), "----abc123");
  EXPECT_EQ(*MultipartBoundary("multipart/form-data; charset=x; BOUNDARY=\"a b:c\""), "a b:c");
  EXPECT_FALSE(MultipartBoundary("multipart/form-data").ok());
  EXPECT_FALSE(MultipartBoundary("multipart/form-data; boundary=").ok());
  EXPECT_FALSE(MultipartBoundary("multipart/form-data; boundary=" + std::string(71, 'a')).ok());
  EXPECT_FALSE(MultipartBoundary("multipart/form-data; boundary=\"a\"b\"").ok());
  EXPECT_FALSE(MultipartBoundary("multipart/form-data; boundary=a{b}").ok());
  EXPECT_FALSE(MultipartBoundary("multipart/form-data; boundary=\"abc").ok());
}

TEST(MultipartFormTest, SplitsPartsWithTheirNamesAndBytes) {
  // Contents with line ends, dashes and a near-boundary stay intact.
  const std::string body = Body({{"mesh", "die.obj", "v 0 0 0\r\n--XyZ-1\r\nf 1 2 3"},
                                 {"mtl", "die.mtl", ""},
                                 {"note", "", "plain field"}});
  auto parts = ParseMultipartForm(body, "XyZ-12");
  ASSERT_TRUE(parts.ok()) << parts.status().ToString();
  ASSERT_EQ(parts->size(), 3u);
  EXPECT_EQ((*parts)[0].name, "mesh");
  EXPECT_EQ((*parts)[0].filename, "die.obj");
  EXPECT_EQ((*parts)[0].bytes, "v 0 0 0\r\n--XyZ-1\r\nf 1 2 3");
  EXPECT_EQ((*parts)[1].bytes, "");
  EXPECT_EQ((*parts)[2].filename, "");
  EXPECT_EQ((*parts)[2].bytes, "plain field");
  // A preamble and an epilogue are ignored; escaped quotes are unescaped.
  const std::string quoted =
      "preamble\r\n--b\r\ncontent-disposition: form-data; name=\"a\"; "
      "filename=\"x\\\"y.ply\"\r\n\r\nbytes\r\n--b--\r\nepilogue";
  parts = ParseMultipartForm(quoted, "b");
  ASSERT_TRUE(parts.ok()) << parts.status().ToString();
  ASSERT_EQ(parts->size(), 1u);
  EXPECT_EQ((*parts)[0].filename, "x\"y.ply");
  EXPECT_EQ((*parts)[0].bytes, "bytes");
}

TEST(MultipartFormTest, RefusesMalformedAndTruncatedBodiesSayingWhy) {
  const std::string good = Body({{"mesh", "a.off", "OFF\n"}});
  struct Case {
    std::string body, message;
  };
  const std::vector<Case> cases = {
      {"", "no boundary line"},
      {"just bytes", "no boundary line"},
      {good.substr(0, good.size() - 10), "truncated"},  // no closing delimiter
      {good.substr(0, 40), "truncated"},                // inside the headers
      {"--XyZ-12", "truncated"},
      {"--XyZ-12--\r\n", "no parts"},
      {"--XyZ-12junk\r\n", "other text"},
      {"--XyZ-12\r\nContent-Type: x\r\n\r\nb\r\n--XyZ-12--", "no Content-Disposition"},
      {"--XyZ-12\r\nContent-Disposition: attachment; name=\"a\"\r\n\r\nb\r\n--XyZ-12--",
       "not form-data"},
      {"--XyZ-12\r\nContent-Disposition: form-data\r\n\r\nb\r\n--XyZ-12--", "has no name"},
      {"--XyZ-12\r\nContent-Disposition: form-data; name=\"a\r\n\r\nb\r\n--XyZ-12--",
       "not closed"},
      {"--XyZ-12\r\nno colon here\r\n\r\nb\r\n--XyZ-12--", "has no name"},
      {"--XyZ-12\r\nX: " + std::string(kMaxFormPartHeaderBytes, 'h') + "\r\n\r\nb\r\n--XyZ-12--",
       "headers over"},
  };
  for (const Case& c : cases) {
    auto parts = ParseMultipartForm(c.body, "XyZ-12");
    ASSERT_FALSE(parts.ok()) << c.body;
    EXPECT_EQ(parts.status().code(), StatusCode::kParseError) << c.body;
    EXPECT_NE(parts.status().message().find(c.message), std::string::npos)
        << parts.status().message();
  }
  std::vector<Part> many(kMaxFormParts + 1, Part{"f", "", "x"});
  EXPECT_NE(ParseMultipartForm(Body(many), "XyZ-12").status().message().find("more than"),
            std::string::npos);
}

TEST(UploadFilesTest, TheMainFileIsTheOneMeshOrTheOneNamed) {
  const std::string body = Body({{"mesh", "die.obj", "v"}, {"mtl", "die.mtl", "m"},
                                 {"tex", "tex/die.png", "p"}});
  auto files = FilesOfMultipart(body, "XyZ-12", std::nullopt);
  ASSERT_TRUE(files.ok()) << files.status().ToString();
  EXPECT_EQ(files->main, "die.obj");
  ASSERT_EQ(files->parts.size(), 3u);
  EXPECT_EQ(files->parts[2].name, "tex/die.png");
  EXPECT_EQ(files->parts[2].bytes, "p");

  const std::string two = Body({{"a", "a.ply", "1"}, {"b", "b.GLB", "2"}});
  auto ambiguous = FilesOfMultipart(two, "XyZ-12", std::nullopt);
  EXPECT_EQ(ambiguous.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(ambiguous.status().message().find("main="), std::string::npos);
  files = FilesOfMultipart(two, "XyZ-12", std::string("b.GLB"));
  ASSERT_TRUE(files.ok());
  EXPECT_EQ(files->main, "b.GLB");
  EXPECT_EQ(FilesOfMultipart(two, "XyZ-12", std::string("c.ply")).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(FilesOfMultipart(body, "XyZ-12", std::string("die.mtl")).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(FilesOfMultipart(Body({{"m", "die.mtl", "m"}}), "XyZ-12", std::nullopt)
                .status()
                .code(),
            StatusCode::kNotFound);
}

TEST(UploadFilesTest, RefusesBadRepeatedOrMissingFileNames) {
  for (const std::vector<Part>& parts : std::vector<std::vector<Part>>{
           {{"a", "a.off", "1"}, {"b", "a.off", "2"}},   // twice
           {{"a", "../a.off", "1"}},                     // leaves the set
           {{"a", "/etc/a.off", "1"}},                   // absolute
           {{"a", "a\\\\b.off", "1"}},                 // a backslash, quoted
           {{"a", "a.off", "1"}, {"b", "", "2"}},        // no filename
       }) {
    auto files = FilesOfMultipart(Body(parts), "XyZ-12", std::nullopt);
    EXPECT_EQ(files.status().code(), StatusCode::kInvalidArgument) << parts.back().filename;
  }
}

TEST(UploadFilesTest, UploadLimitsFollowTheServerConfiguration) {
  proto::ServerConfig config;
  config.set_upload_limit_bytes(1000);
  AssetLimits limits = UploadAssetLimits(config);
  EXPECT_EQ(limits.max_file_bytes, 1000u);
  EXPECT_EQ(limits.max_image_pixels, AssetLimits{}.max_image_pixels);
  config.set_ingest_memory_limit_bytes(uint64_t{1} << 28);  // 256 MiB
  limits = UploadAssetLimits(config);
  EXPECT_EQ(limits.max_image_bytes, uint64_t{1} << 26);
  EXPECT_EQ(limits.max_image_pixels, uint64_t{1} << 24);  // a 4096 x 4096 image
}

}  // namespace
}  // namespace meshwave::server
