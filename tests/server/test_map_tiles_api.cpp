// The map background's routes (GET /api/v1/tiles, /api/v1/tiles/{z}/{x}/{y}) over a tile folder:
// the image with its type and caching, 404 and 400 as problem+json, nothing outside the folder
// whatever the path says, and the token as ?token= (an <img> cannot send a header) from
// elsewhere. Through the router, then through the real transport (which decodes the path).
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "server/http/http_server.hpp"
#include "server/map_tile_routes.hpp"
#include "server/stream_hub.hpp"
#include "support/http_client.hpp"

namespace {

namespace fs = std::filesystem;
using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::Router;
using nlohmann::json;

constexpr const char* kToken = "map-tiles-token-0123456789-abcdefghijKLMN";
const std::string kPng = std::string("\x89PNG\r\n\x1a\n", 8) + "harbour";
const std::string kSecret = std::string("\x89PNG\r\n\x1a\n", 8) + "SECRET-outside-the-folder";

class MapTilesApi : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    base_ = fs::temp_directory_path() /
            ("avk_tiles_api_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(base_);
    // The tiles, and beside them files a traversal would reach: a secret image and a tile-like
    // one at ../1/0/0.png relative to a level.
    write(base_ / "tiles/1/0/0.png", kPng);
    write(base_ / "tiles/1/1/1.png", kPng);
    write(base_ / "secret.png", kSecret);
    write(base_ / "1/0/0.png", kSecret);
    auto opened = avk::app::tiles::open_map_tiles((base_ / "tiles").string());
    ASSERT_TRUE(opened) << opened.error().message;
    tiles_ = *opened;
    avk::server::add_map_tile_routes(router_, tiles_, avk::vehicle::LatLon{42.358456, -71.087589});
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(base_, ec);
  }
  static void write(const fs::path& p, const std::string& bytes) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
  }
  ApiResponse get(const std::string& path, bool loopback = true,
                  std::map<std::string, std::string> query = {}) {
    ApiRequest r;
    r.method = "GET";
    r.path = path;
    r.remote_is_loopback = loopback;
    r.query = std::move(query);
    return router_.handle(r);
  }

  fs::path base_;
  std::shared_ptr<const avk::app::tiles::MapTiles> tiles_;
  Router router_{kToken};
};

std::string header(const ApiResponse& r, const std::string& name) {
  for (const auto& [k, v] : r.headers)
    if (k == name) return v;
  return "";
}

TEST_F(MapTilesApi, TheInfoSaysWhatThePageNeeds) {
  const auto r = get("/api/v1/tiles");
  ASSERT_EQ(r.status, 200) << r.body;
  const json j = json::parse(r.body);
  EXPECT_EQ(j["available"], true);
  EXPECT_EQ(j["source"], "folder");
  EXPECT_EQ(j["format"], "png");
  EXPECT_EQ(j["minzoom"], 1);
  EXPECT_EQ(j["maxzoom"], 1);
  ASSERT_TRUE(j["bounds"].is_array());
  EXPECT_DOUBLE_EQ(j["bounds"][0].get<double>(), -180.0);
  EXPECT_DOUBLE_EQ(j["bounds"][2].get<double>(), 180.0);
  EXPECT_EQ(j["tile_url"], "/api/v1/tiles/{z}/{x}/{y}");
  EXPECT_DOUBLE_EQ(j["datum"]["lat_deg"].get<double>(), 42.358456);
}

TEST(MapTilesApiWithout, NoTilesIsAnAnswerAndEveryTileA404) {
  Router router(kToken);
  avk::server::add_map_tile_routes(router, nullptr, std::nullopt);
  ApiRequest r;
  r.method = "GET";
  r.path = "/api/v1/tiles";
  const auto info = router.handle(r);
  ASSERT_EQ(info.status, 200);
  const json j = json::parse(info.body);
  EXPECT_EQ(j["available"], false);
  EXPECT_TRUE(j["source"].is_null());
  EXPECT_TRUE(j["bounds"].is_null());
  EXPECT_TRUE(j["datum"].is_null());
  r.path = "/api/v1/tiles/1/0/0";
  const auto tile = router.handle(r);
  EXPECT_EQ(tile.status, 404);
  EXPECT_NE(tile.body.find("--tiles"), std::string::npos) << tile.body;
}

TEST_F(MapTilesApi, ATileIsTheImageWithItsTypeAndCaching) {
  const auto r = get("/api/v1/tiles/1/0/0");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.content_type, "image/png");
  EXPECT_EQ(r.body, kPng);
  EXPECT_EQ(header(r, "Cache-Control"), avk::server::kTileCacheControl);
}

TEST_F(MapTilesApi, AMissingTileIs404NamingIt) {
  const auto r = get("/api/v1/tiles/1/1/0");
  EXPECT_EQ(r.status, 404);
  EXPECT_EQ(r.content_type, "application/problem+json");
  EXPECT_NE(json::parse(r.body)["detail"].get<std::string>().find("1/1/0"), std::string::npos)
      << r.body;
}

TEST_F(MapTilesApi, ACoordinateThatIsNotAWholeNumberInRangeIs400NamingIt) {
  struct Case {
    const char* path;
    const char* parameter;
  };
  for (const Case& c :
       {Case{"/api/v1/tiles/1/0/0.png", "y"}, Case{"/api/v1/tiles/1/-1/0", "x"},
        Case{"/api/v1/tiles/+1/0/0", "z"}, Case{"/api/v1/tiles/1/0x1/0", "x"},
        Case{"/api/v1/tiles/1/0/1e0", "y"}, Case{"/api/v1/tiles/25/0/0", "z"},
        Case{"/api/v1/tiles/1/2/0", "x"}, Case{"/api/v1/tiles/1/0/2", "y"},
        Case{"/api/v1/tiles/1/0/9999999999", "y"}, Case{"/api/v1/tiles/1/0/..", "y"},
        Case{"/api/v1/tiles/../0/0", "z"}, Case{"/api/v1/tiles/1/../0", "x"}}) {
    const auto r = get(c.path);
    EXPECT_EQ(r.status, 400) << c.path << ": " << r.body;
    EXPECT_EQ(r.content_type, "application/problem+json");
    const json j = json::parse(r.body);
    EXPECT_EQ(j["parameter"], c.parameter) << c.path;
  }
}

// The router splits the decoded path at '/': a path with more segments is no tile route, and
// one with the right number names coordinates that are not numbers. Either way no file is read.
TEST_F(MapTilesApi, NoPathReachesAFileOutsideTheFolder) {
  for (const char* path : {"/api/v1/tiles/1/0/../../../secret.png", "/api/v1/tiles/../1/0/0",
                           "/api/v1/tiles/1/0/..%2F..%2Fsecret",
                           "/api/v1/tiles/1/0/0/../../../../1/0/0", "/api/v1/tiles/%2e%2e/1/0/0"}) {
    const auto r = get(path);
    EXPECT_TRUE(r.status == 400 || r.status == 404) << path << ": " << r.status;
    EXPECT_EQ(r.body.find("SECRET"), std::string::npos) << path;
  }
}

// Regression: a link in the folder to a file outside it (/etc/passwd, the station's token file)
// was served as image/png. Now it is a 404 that says why and carries none of the file.
TEST_F(MapTilesApi, ALinkOutOfTheFolderOrAFileThatIsNoImageIs404) {
  write(base_ / "station.db.token", "SECRET-token-0123456789abcdef\n");
  fs::create_directories(base_ / "tiles/2/0");
  fs::create_symlink(base_ / "station.db.token", base_ / "tiles/2/0/0.png");
  fs::create_symlink(base_ / "secret.png", base_ / "tiles/2/0/1.png");
  write(base_ / "tiles/2/0/2.png", "SECRET but no image\n");
  for (const char* path : {"/api/v1/tiles/2/0/0", "/api/v1/tiles/2/0/1", "/api/v1/tiles/2/0/2"}) {
    const auto r = get(path);
    EXPECT_EQ(r.status, 404) << path << ": " << r.body;
    EXPECT_EQ(r.content_type, "application/problem+json") << path;
    EXPECT_EQ(r.body.find("SECRET"), std::string::npos) << path;
  }
  EXPECT_NE(get("/api/v1/tiles/2/0/0").body.find("leaves the tile folder"), std::string::npos);
  EXPECT_NE(get("/api/v1/tiles/2/0/2").body.find("not a PNG, JPEG or WebP image"),
            std::string::npos);
}

TEST_F(MapTilesApi, FromElsewhereATileTakesTheTokenAsAQueryParameter) {
  EXPECT_EQ(get("/api/v1/tiles/1/0/0", false).status, 401);
  EXPECT_EQ(get("/api/v1/tiles/1/0/0", false, {{"token", "wrong"}}).status, 401);
  const auto r = get("/api/v1/tiles/1/0/0", false, {{"token", kToken}});
  EXPECT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.body, kPng);
  // The header works as on every route; ?token= only where a browser cannot send one.
  ApiRequest h;
  h.method = "GET";
  h.path = "/api/v1/tiles";
  h.remote_is_loopback = false;
  h.query = {{"token", kToken}};
  EXPECT_EQ(router_.handle(h).status, 401);
  h.authorization = std::string("Bearer ") + kToken;
  EXPECT_EQ(router_.handle(h).status, 200);
  // The transport asks admit() first, from the header alone: the same rule.
  ApiRequest head;
  head.method = "GET";
  head.path = "/api/v1/tiles/1/0/0";
  head.remote_is_loopback = false;
  EXPECT_TRUE(router_.admit(head).refusal);
  head.query = {{"token", kToken}};
  EXPECT_FALSE(router_.admit(head).refusal);
}

// Through the real transport, which percent-decodes the path before the router sees it.
TEST_F(MapTilesApi, OverHttpTheImageComesAndTraversalsDoNot) {
  avk::server::StreamHub hub;
  avk::server::HttpServer server(avk::server::HttpServerOptions{}, router_, hub);
  server.start();
  const auto port = server.port();
  const auto ok = avk::testing::http_call(port, "GET", "/api/v1/tiles/1/1/1");
  EXPECT_EQ(ok.status, 200);
  EXPECT_EQ(ok.body, kPng);
  EXPECT_EQ(ok.headers.at("Content-Type"), "image/png");
  EXPECT_EQ(ok.headers.at("Cache-Control"), avk::server::kTileCacheControl);
  for (const char* target :
       {"/api/v1/tiles/1/0/..%2F..%2F..%2Fsecret.png", "/api/v1/tiles/%2E%2E/1/0/0",
        "/api/v1/tiles/1/0/%2e%2e", "/api/v1/tiles/1/0/0%00.png",
        "/api/v1/tiles/1/0/..%2F..%2F1%2F0%2F0"}) {
    const auto r = avk::testing::http_call(port, "GET", target);
    EXPECT_TRUE(r.status == 400 || r.status == 404) << target << ": " << r.status;
    EXPECT_EQ(r.body.find("SECRET"), std::string::npos) << target;
  }
  server.stop();
}

}  // namespace
