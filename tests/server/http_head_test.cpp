// Response heads written by hand: the same fields as Beast's serializer
// writes after the session's finishing touches, Content-Length where HTTP
// wants it, and the Connection field of each version.
#include "http_head.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

namespace meshwave::server {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find("\r\n", at);
    if (end == std::string::npos) break;
    lines.push_back(text.substr(at, end - at));
    at = end + 2;
  }
  return lines;
}

TEST(HttpHeadTest, StatusLineNamesVersionCodeAndReason) {
  std::string s;
  AppendStatusLine(s, 11, 200);
  EXPECT_EQ(s, "HTTP/1.1 200 OK\r\n");
  s.clear();
  AppendStatusLine(s, 10, 404);
  EXPECT_EQ(s, "HTTP/1.0 404 Not Found\r\n");
  s.clear();
  AppendStatusLine(s, 11, 416);
  EXPECT_EQ(s, "HTTP/1.1 416 Range Not Satisfiable\r\n");
}

TEST(HttpHeadTest, WritesWhatBeastWritesForTheSameResponse) {
  Response r{http::status::ok, 11};
  r.set(http::field::content_type, "application/octet-stream");
  r.set(http::field::etag, "\"abc-p3\"");
  r.set(http::field::cache_control, "public, max-age=31536000, immutable");
  r.set("X-Meshwave-Packets", "7");
  r.body().owned = std::string(1234, 'x');

  std::string ours;
  AppendStatusLine(ours, 11, 200);
  AppendFields(ours, r, r.body().size(), false);
  ours += ConnectionField(11, true);
  ours += "\r\n";

  // What HttpSession did before: Beast's header after keep_alive, Server
  // and prepare_payload.
  http::response<http::string_body> beast{http::status::ok, 11};
  for (const auto& f : r) beast.set(f.name_string(), f.value());
  beast.body() = r.body().owned;
  beast.keep_alive(true);
  beast.set(http::field::server, "meshwave");
  beast.prepare_payload();
  std::ostringstream os;
  os << beast.base();
  auto a = Lines(ours), b = Lines(os.str());
  EXPECT_EQ(a.front(), b.front());  // the status line
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b) << ours << "\n---\n" << os.str();
}

TEST(HttpHeadTest, ContentLengthExceptFor1xx204And304ButAlwaysForHead) {
  EXPECT_TRUE(SendsContentLength(200, false));
  EXPECT_TRUE(SendsContentLength(404, false));
  EXPECT_FALSE(SendsContentLength(204, false));
  EXPECT_FALSE(SendsContentLength(304, false));
  EXPECT_FALSE(SendsContentLength(100, false));
  EXPECT_TRUE(SendsContentLength(304, true));

  Response not_modified{http::status::not_modified, 11};
  not_modified.set(http::field::etag, "\"t\"");
  std::string s;
  AppendFields(s, not_modified, 0, false);
  EXPECT_EQ(s, "ETag: \"t\"\r\nServer: meshwave\r\n");
}

TEST(HttpHeadTest, LeavesOutTheFieldsTheSessionDecides) {
  Response r{http::status::ok, 11};
  r.set(http::field::server, "other");
  r.set(http::field::content_length, "5");
  r.set(http::field::connection, "close");
  r.set(http::field::vary, "Accept");
  std::string s;
  AppendFields(s, r, 12, false);
  EXPECT_EQ(s, "Vary: Accept\r\nServer: meshwave\r\nContent-Length: 12\r\n");
}

TEST(HttpHeadTest, ConnectionFieldOnlyWhereItDiffersFromTheVersionsDefault) {
  EXPECT_EQ(ConnectionField(11, true), "");
  EXPECT_EQ(ConnectionField(11, false), "Connection: close\r\n");
  EXPECT_EQ(ConnectionField(10, true), "Connection: keep-alive\r\n");
  EXPECT_EQ(ConnectionField(10, false), "");
}

}  // namespace
}  // namespace meshwave::server
