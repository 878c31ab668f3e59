// The live stream's token: off loopback every request needs the station's bearer token, and a
// browser cannot set headers on a WebSocket, so the dashboard sends it as `?token=` on the
// upgrade. Reproduces the Docker deployment's defect: the stream had no way to carry the token
// and let any address in.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "server/api_types.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "server/stream_hub.hpp"
#include "support/temp_db.hpp"

namespace {

namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace net = boost::asio;
using tcp = boost::asio::ip::tcp;
using namespace std::chrono_literals;

using avk::server::Api;
using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::HttpServer;
using avk::server::HttpServerOptions;
using avk::server::StreamHub;

constexpr const char* kToken = "stream-token-0123456789abcdef";

// Lets the stream open only with the token, and records what the transport passed.
class TokenApi final : public Api {
 public:
  ApiResponse handle(const ApiRequest&) override { return {}; }
  bool may_open_stream(const ApiRequest& r) override {
    std::lock_guard lock(mutex);
    seen.push_back(r.authorization);
    return r.authorization == std::string("Bearer ") + kToken;
  }
  std::mutex mutex;
  std::vector<std::string> seen;
};

// One raw upgrade request; the status line of the answer (bounded by a 10 s deadline). From
// `address` to the server listening there: a non-loopback address of this machine makes the
// server see a client that is not on loopback.
http::response<http::string_body> upgrade(unsigned short port, const std::string& target,
                                          const std::string& authorization = "",
                                          const std::string& address = "127.0.0.1") {
  net::io_context io;
  beast::tcp_stream stream(io);
  stream.expires_after(10s);
  stream.connect(tcp::endpoint(net::ip::make_address(address), port));
  http::request<http::empty_body> req(http::verb::get, target, 11);
  req.set(http::field::host, address + ":" + std::to_string(port));
  req.set(http::field::upgrade, "websocket");
  req.set(http::field::connection, "Upgrade");
  req.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
  req.set(http::field::sec_websocket_version, "13");
  if (!authorization.empty()) req.set(http::field::authorization, authorization);
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.skip(false);
  http::read_header(stream, buffer, parser);
  auto res = parser.release();
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  return res;
}

class StreamToken : public ::testing::Test {
 protected:
  void SetUp() override {
    HttpServerOptions o;
    o.server_version = "test";
    server_ = std::make_unique<HttpServer>(o, api_, hub_);
    server_->start();
  }
  void TearDown() override { server_->stop(); }

  TokenApi api_;
  StreamHub hub_;
  std::unique_ptr<HttpServer> server_;
};

TEST_F(StreamToken, AQueryTokenReachesTheApiAsTheBearerToken) {
  const auto res = upgrade(server_->port(), std::string("/api/v1/stream?token=") + kToken);
  EXPECT_EQ(res.result_int(), 101);
  std::lock_guard lock(api_.mutex);
  ASSERT_EQ(api_.seen.size(), 1u);
  EXPECT_EQ(api_.seen[0], std::string("Bearer ") + kToken);
}

TEST_F(StreamToken, APercentEncodedQueryTokenIsDecoded) {
  // "stream-token-…" with its dashes encoded, as encodeURIComponent may send other characters.
  std::string encoded;
  for (const char c : std::string(kToken))
    encoded += c == '-' ? std::string("%2D") : std::string(1, c);
  EXPECT_EQ(upgrade(server_->port(), "/api/v1/stream?token=" + encoded).result_int(), 101);
}

TEST_F(StreamToken, AnAuthorizationHeaderIsUsedAsIs) {
  const auto res = upgrade(server_->port(), "/api/v1/stream", std::string("Bearer ") + kToken);
  EXPECT_EQ(res.result_int(), 101);
}

TEST_F(StreamToken, AWrongOrMissingTokenIs401WithProblemJsonAndNoUpgrade) {
  for (const std::string target : {"/api/v1/stream?token=wrong", "/api/v1/stream"}) {
    const auto res = upgrade(server_->port(), target);
    EXPECT_EQ(res.result_int(), 401) << target;
    EXPECT_EQ(res[http::field::www_authenticate], "Bearer") << target;
    EXPECT_EQ(res[http::field::content_type], "application/problem+json") << target;
  }
}

// A station with the test's token and no vehicle.
avk::server::StationOptions station_options(const avk::testing::TempDb& db) {
  avk::server::StationOptions o;
  o.db_path = db.path();
  o.token = kToken;
  o.server_version = "test";
  return o;
}

// The station's rule: the stream is open on loopback, and needs the token from anywhere else.
TEST(StationStreamRule, OffLoopbackTheStreamNeedsTheToken) {
  avk::testing::TempDb db{"avk_stream_token"};
  StreamHub hub;
  avk::server::Station station(station_options(db), hub);

  ApiRequest r;
  r.method = "GET";
  r.path = "/api/v1/stream";
  r.remote_is_loopback = true;
  EXPECT_TRUE(station.may_open_stream(r)) << "loopback reads are open";
  r.remote_is_loopback = false;
  r.remote_address = "10.213.0.2";
  EXPECT_FALSE(station.may_open_stream(r)) << "no token from off this machine";
  r.authorization = "Bearer wrong";
  EXPECT_FALSE(station.may_open_stream(r));
  r.authorization = std::string("Bearer ") + kToken;
  EXPECT_TRUE(station.may_open_stream(r));
}

// An IPv4 address of this machine that is not loopback (a container's eth0), if it has one.
std::optional<std::string> non_loopback_ipv4() {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return std::nullopt;
  std::optional<std::string> found;
  for (ifaddrs* a = list; a && !found; a = a->ifa_next) {
    if (!a->ifa_addr || a->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
    if (!inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) continue;
    if (!net::ip::make_address_v4(text).is_loopback()) found = text;
  }
  freeifaddrs(list);
  return found;
}

// The whole way, as a client on another machine meets it: the real station behind the real
// transport, reached from an address that is not loopback. The doc says every
// request from afar needs the token; the stream must take it (header or ?token=) and refuse
// without it.
TEST(StationStreamRule, FromAnotherAddressTheStreamTakesTheTokenAndRefusesWithoutIt) {
  const auto address = non_loopback_ipv4();
  if (!address) GTEST_SKIP() << "this machine has no non-loopback IPv4 address";
  avk::testing::TempDb db{"avk_stream_token_remote"};
  StreamHub hub;
  avk::server::Station station(station_options(db), hub);
  HttpServerOptions o;
  o.server_version = "test";
  o.bind_address = *address;
  HttpServer server(o, station, hub);
  server.start();
  const auto port = server.port();

  const auto without = upgrade(port, "/api/v1/stream", "", *address);
  EXPECT_EQ(without.result_int(), 401);
  EXPECT_EQ(without[http::field::www_authenticate], "Bearer");
  EXPECT_EQ(upgrade(port, "/api/v1/stream?token=wrong", "", *address).result_int(), 401);
  EXPECT_EQ(upgrade(port, "/api/v1/stream", "Bearer wrong", *address).result_int(), 401);
  EXPECT_EQ(upgrade(port, std::string("/api/v1/stream?token=") + kToken, "", *address).result_int(),
            101);
  EXPECT_EQ(upgrade(port, "/api/v1/stream", std::string("Bearer ") + kToken, *address).result_int(),
            101);
  server.stop();
}

}  // namespace
