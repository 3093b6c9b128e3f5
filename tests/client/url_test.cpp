#include "meshwave/client/url.h"

#include <gtest/gtest.h>

namespace meshwave::client {
namespace {

TEST(UrlTest, ParsesMeshUrlWithPort) {
  auto u = ParseMeshUrl("http://127.0.0.1:8080/v1/meshes/0123456789ab");
  ASSERT_TRUE(u.ok()) << u.status().ToString();
  EXPECT_FALSE(u->server.tls);
  EXPECT_EQ(u->server.host, "127.0.0.1");
  EXPECT_EQ(u->server.port, 8080);
  EXPECT_EQ(u->mesh_id, "0123456789ab");
  EXPECT_EQ(u->Path(), "/v1/meshes/0123456789ab");
  EXPECT_EQ(u->ToString(), "http://127.0.0.1:8080/v1/meshes/0123456789ab");
}

TEST(UrlTest, DefaultPortsFollowTheScheme) {
  auto http = ParseMeshUrl("HTTP://example.org/v1/meshes/0123456789ab/");
  ASSERT_TRUE(http.ok());
  EXPECT_EQ(http->server.port, 80);
  auto https = ParseServerUrl("https://example.org/");
  ASSERT_TRUE(https.ok());
  EXPECT_TRUE(https->tls);
  EXPECT_EQ(https->port, 443);
}

TEST(UrlTest, AcceptsBracketedIpv6) {
  auto u = ParseServerUrl("http://[::1]:9000");
  ASSERT_TRUE(u.ok()) << u.status().ToString();
  EXPECT_EQ(u->host, "::1");
  EXPECT_EQ(u->port, 9000);
  EXPECT_EQ(u->ToString(), "http://[::1]:9000");
}

TEST(UrlTest, RejectsMalformedUrls) {
  for (const char* bad :
       {"", "ftp://h/v1/meshes/0123456789ab", "http://",
        "http://:80/v1/meshes/0123456789ab",
        "http://u:p@h/v1/meshes/0123456789ab",
        "http://h/v1/meshes/0123456789ab?x=1",
        "http://h/v1/meshes/0123456789ab#f",
        "http://h:0/v1/meshes/0123456789ab",
        "http://h:65536/v1/meshes/0123456789ab",
        "http://h:8x/v1/meshes/0123456789ab",
        "http://h:/v1/meshes/0123456789ab", "http://h/v1/meshes/0123456789AB",
        "http://h/v1/meshes/0123456789a", "http://h/v1/meshes/",
        "http://h/v2/x", "http://h/v1/meshes/0123456789ab/header",
        "http://h h/v1/meshes/0123456789ab",
        "http://[::1/v1/meshes/0123456789ab",
        "http://[::1]x/v1/meshes/0123456789ab"}) {
    auto u = ParseMeshUrl(bad);
    EXPECT_FALSE(u.ok()) << bad;
    if (!u.ok()) {
      EXPECT_EQ(u.status().code(), StatusCode::kInvalidArgument) << bad;
    }
  }
  EXPECT_FALSE(ParseServerUrl("http://h:80/v1/meshes").ok());
}

TEST(UrlTest, WebSocketSchemesChooseTheWebSocketTransport) {
  auto ws = ParseMeshUrl("ws://h/v1/meshes/0123456789ab");
  ASSERT_TRUE(ws.ok()) << ws.status().ToString();
  EXPECT_TRUE(ws->server.websocket);
  EXPECT_FALSE(ws->server.tls);
  EXPECT_EQ(ws->server.port, 80);
  EXPECT_EQ(ws->ToString(), "ws://h:80/v1/meshes/0123456789ab");
  auto wss = ParseMeshUrl("WSS://[::1]:8443/v1/meshes/0123456789ab/");
  ASSERT_TRUE(wss.ok()) << wss.status().ToString();
  EXPECT_TRUE(wss->server.websocket);
  EXPECT_TRUE(wss->server.tls);
  EXPECT_EQ(wss->ToString(), "wss://[::1]:8443/v1/meshes/0123456789ab");
  EXPECT_EQ(ParseMeshUrl(wss->ToString())->ToString(), wss->ToString());
  auto http = ParseMeshUrl("http://h/v1/meshes/0123456789ab");
  ASSERT_TRUE(http.ok());
  EXPECT_FALSE(http->server.websocket);
  EXPECT_FALSE(ParseMeshUrl("wss:/h/v1/meshes/0123456789ab").ok());
  EXPECT_FALSE(ParseMeshUrl("ftp://h/v1/meshes/0123456789ab").ok());
}

}  // namespace
}  // namespace meshwave::client
