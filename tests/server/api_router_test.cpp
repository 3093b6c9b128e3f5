// The routes' rule for the response cache (ResponseCacheKey, api_router.h):
// which requests may be answered from it, and the key, which must hold
// every request field the mesh endpoints read.
#include "api_router.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>

namespace meshwave::server {
namespace {

http::request_header<> Get(const std::string& target, http::verb method = http::verb::get) {
  http::request_header<> h;
  h.method(method);
  h.target(target);
  h.version(11);
  return h;
}

TEST(ApiRouterTest, TheMeshEndpointsGetsAreCachedUnderTheirTarget) {
  for (const char* target : {"/v1/meshes/0123456789ab", "/v1/meshes/0123456789ab/header",
                             "/v1/meshes/0123456789ab/stream?order=rd&budget=8000",
                             "/v1/meshes/0123456789ab/packets/3",
                             "/v1/meshes/0123456789ab/container"}) {
    EXPECT_EQ(ResponseCacheKey(Get(target)), std::optional<std::string>(target)) << target;
    EXPECT_EQ(ResponseCacheKey(Get(target, http::verb::head)), std::optional<std::string>(target));
  }
}

TEST(ApiRouterTest, RangeFieldsArePartOfTheKey) {
  auto h = Get("/v1/meshes/0123456789ab/container");
  h.set(http::field::range, "bytes=0-9");
  EXPECT_EQ(ResponseCacheKey(h), "/v1/meshes/0123456789ab/container\nbytes=0-9\n");
  h.set(http::field::if_range, "\"x\"");
  EXPECT_EQ(ResponseCacheKey(h), "/v1/meshes/0123456789ab/container\nbytes=0-9\n\"x\"");
}

TEST(ApiRouterTest, OtherRequestsAreNotCached) {
  auto conditional = Get("/v1/meshes/0123456789ab/header");
  conditional.set(http::field::if_none_match, "\"x\"");
  EXPECT_FALSE(ResponseCacheKey(conditional));  // the handlers answer 304
  EXPECT_FALSE(ResponseCacheKey(Get("/v1/meshes?limit=5")));  // the listing changes
  EXPECT_FALSE(ResponseCacheKey(Get("/v1/meshes")));
  EXPECT_FALSE(ResponseCacheKey(Get("/healthz")));
  EXPECT_FALSE(ResponseCacheKey(Get("/metrics")));
  EXPECT_FALSE(ResponseCacheKey(Get("/viewer/index.html")));
  EXPECT_FALSE(ResponseCacheKey(Get("/v1/meshes/0123456789ab", http::verb::delete_)));
  EXPECT_FALSE(ResponseCacheKey(Get("/v1/meshes/", http::verb::post)));
}

}  // namespace
}  // namespace meshwave::server
