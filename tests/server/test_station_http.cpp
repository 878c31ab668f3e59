// The Station behind the real transport, attacked as a hostile client would: what the
// header decides (the token, the route's body limit) before any body is read, nesting depth,
// encodings, HEAD and the bearer scheme. Every exchange is a raw socket with a deadline.

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/mission_mcap.hpp"
#include "app/store_access.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

namespace app = avk::app;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr const char* kToken = "station-http-token-0123456789-abcdefghijKLMN";

// Sends bytes on a fresh loopback connection and returns everything until the server closes or
// the deadline passes.
std::string send_and_read(unsigned short port, const std::string& bytes,
                          std::chrono::milliseconds limit = 20000ms) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    throw std::runtime_error("connect");
  }
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const auto n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may answer and close before it has read everything
    sent += static_cast<std::size_t>(n);
  }
  std::string out;
  const auto deadline = Clock::now() + limit;
  char b[65536];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    const auto n = ::recv(fd, b, sizeof b, 0);
    if (n <= 0) break;
    out.append(b, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return out;
}

int status_of(const std::string& raw) {
  if (raw.size() < 12 || !raw.starts_with("HTTP/1.")) return 0;
  return std::stoi(raw.substr(9, 3));
}

std::string header_value(const std::string& raw, const std::string& name) {
  const auto at = raw.find("\r\n" + name + ": ");
  if (at == std::string::npos) return {};
  const auto start = at + name.size() + 4;
  return raw.substr(start, raw.find("\r\n", start) - start);
}

std::string body_of(const std::string& raw) {
  const auto end = raw.find("\r\n\r\n");
  return end == std::string::npos ? std::string() : raw.substr(end + 4);
}

std::string request(const std::string& method, const std::string& target,
                    const std::string& body = "", const std::string& extra_headers = "") {
  return method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
         extra_headers + (body.empty() ? "" : "Content-Type: application/json\r\n") +
         "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

class StationHttpTest : public ::testing::Test {
 protected:
  void SetUp() override {
    avk::server::StationOptions so;
    so.db_path = db.path();
    so.token = kToken;
    so.server_version = "test";
    station = std::make_unique<avk::server::Station>(so, hub);
    station->start();
    server =
        std::make_unique<avk::server::HttpServer>(avk::server::HttpServerOptions{}, *station, hub);
    server->start();
    port = server->port();
  }
  void TearDown() override {
    server.reset();
    station.reset();
  }

  avk::testing::TempDb db{"avk_station_http"};
  avk::server::StreamHub hub;
  std::unique_ptr<avk::server::Station> station;
  std::unique_ptr<avk::server::HttpServer> server;
  unsigned short port = 0;
};

// Regression: {"missions": [[[...]]]} 100,000 deep crashed the server (58,165 frames in
// the serialiser under the model-fit handler).
TEST_F(StationHttpTest, DeeplyNestedFitRequestIs400AndTheServerGoesOn) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const auto raw = send_and_read(
      port, request("POST", "/api/v1/vehicles/sim-usim/models", "{\"missions\":" + deep + "}",
                    std::string("Authorization: Bearer ") + kToken + "\r\n"));
  EXPECT_EQ(status_of(raw), 400) << raw.substr(0, 400);
  EXPECT_LT(raw.size(), 2000u);  // nothing of the input echoed whole
  // A shallow container in the wrong place is named by its kind, not dumped.
  const auto shallow =
      send_and_read(port, request("POST", "/api/v1/vehicles/sim-usim/models",
                                  "{\"missions\":[[\"" + std::string(5000, 'x') + "\"]]}",
                                  std::string("Authorization: Bearer ") + kToken + "\r\n"));
  EXPECT_EQ(status_of(shallow), 422) << shallow.substr(0, 400);
  EXPECT_EQ(shallow.find("xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx"), std::string::npos);
  EXPECT_EQ(status_of(send_and_read(port, request("GET", "/api/v1/health"))), 200);
}

// Regression: without a token, the server first read the 62 MB body, then said 401.
// The header is all it reads now: the answer comes although the body is never sent.
TEST_F(StationHttpTest, ImportWithoutTheTokenIs401BeforeTheBody) {
  const auto raw = send_and_read(port,
                                 "POST /api/v1/vehicles/sim-usim/ckt/import HTTP/1.1\r\n"
                                 "Host: 127.0.0.1\r\nContent-Type: text/csv\r\n"
                                 "Content-Length: 62000000\r\n\r\nspeed",
                                 20000ms);
  EXPECT_EQ(status_of(raw), 401) << raw;
  EXPECT_EQ(header_value(raw, "WWW-Authenticate"), "Bearer");
  // The import route's own limit is the Station's: 64 MB passes the header check, more is 413.
  const auto huge = send_and_read(port,
                                  "POST /api/v1/vehicles/sim-usim/ckt/import HTTP/1.1\r\n"
                                  "Host: 127.0.0.1\r\nAuthorization: Bearer " +
                                      std::string(kToken) + "\r\nContent-Length: 70000000\r\n\r\n");
  EXPECT_EQ(status_of(huge), 413) << huge;
  // Other routes keep the transport's 1 MB.
  const auto big = send_and_read(port,
                                 "POST /api/v1/vehicles/sim-usim/missions HTTP/1.1\r\n"
                                 "Host: 127.0.0.1\r\nAuthorization: Bearer " +
                                     std::string(kToken) + "\r\nContent-Length: 2000000\r\n\r\n");
  EXPECT_EQ(status_of(big), 413) << big;
}

// Regression: "bearer" in lower case (RFC 7235: the scheme is case-insensitive) was refused.
TEST_F(StationHttpTest, TheBearerSchemeIsCaseInsensitive) {
  for (const std::string scheme : {"Bearer", "bearer", "BEARER", "bEaReR"}) {
    const auto raw =
        send_and_read(port, request("POST", "/api/v1/missions/99/pause", "",
                                    "Authorization: " + scheme + " " + kToken + "\r\n"));
    EXPECT_EQ(status_of(raw), 404) << scheme << "\n" << raw;  // past the token: no mission 99
  }
  for (const std::string& wrong :
       {std::string("Bearer ") + kToken + "x",
        std::string("Bearer ") + std::string(kToken).substr(1), std::string("Basic ") + kToken,
        std::string("Bearer"), std::string("Bearer") + kToken}) {
    const auto raw = send_and_read(
        port, request("POST", "/api/v1/missions/99/pause", "", "Authorization: " + wrong + "\r\n"));
    EXPECT_EQ(status_of(raw), 401) << wrong;
  }
}

// Regression: HEAD on an API route answered Content-Length: 0.
TEST_F(StationHttpTest, HeadGivesTheGetsHeadersAndNoBody) {
  for (const std::string path :
       {"/api/v1/health", "/api/v1/vehicles", "/api/v1/missions", "/api/v1/missions?format=csv",
        "/api/v1/turns", "/api/v1/vehicles/sim-usim", "/api/v1/vehicles/nobody/ckt",
        "/api/v1/models/12345"}) {
    const auto get = send_and_read(port, request("GET", path));
    const auto head_then_get = send_and_read(
        port, "HEAD " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n" + request("GET", path));
    EXPECT_EQ(status_of(head_then_get), status_of(get)) << path;
    EXPECT_EQ(header_value(head_then_get, "Content-Type"), header_value(get, "Content-Type"))
        << path;
    EXPECT_EQ(header_value(head_then_get, "Content-Length"), std::to_string(body_of(get).size()))
        << path;
    EXPECT_NE(header_value(head_then_get, "Content-Length"), "0") << path;
    // The GET's response follows the HEAD's header at once: no body in between.
    const auto second = body_of(head_then_get);
    EXPECT_TRUE(second.starts_with("HTTP/1.1 ")) << head_then_get;
    EXPECT_EQ(status_of(second), status_of(get)) << path;
  }
}

// The MCAP export is written to a temporary file and sent from it: the same file as the one made
// in memory, with its length announced (HEAD too) and nothing else in the body.
TEST_F(StationHttpTest, TheMcapExportIsSentFromAFileWhole) {
  const auto mission =
      avk::testing::store_arc_turns(avk::app::store_of(station->context()), "alpha", 1.0, 3);
  app::McapExportOptions o;
  o.compression = app::mcap::Compression::none;
  const auto expected = app::export_mission_mcap(station->context(), mission, o);
  ASSERT_TRUE(expected) << expected.error().message;
  const std::string target =
      "/api/v1/missions/" + std::to_string(mission) + "/export?format=mcap&compression=none";
  const auto raw = send_and_read(port, request("GET", target));
  ASSERT_EQ(status_of(raw), 200) << raw.substr(0, 400);
  EXPECT_EQ(header_value(raw, "Content-Type"), "application/vnd.mcap");
  EXPECT_EQ(header_value(raw, "Content-Disposition"),
            "attachment; filename=\"mission-" + std::to_string(mission) + ".mcap\"");
  EXPECT_EQ(header_value(raw, "Content-Length"), std::to_string(expected->bytes.size()));
  EXPECT_TRUE(body_of(raw) == expected->bytes) << body_of(raw).size() << " bytes";
  const auto head = send_and_read(port, request("HEAD", target));
  EXPECT_EQ(status_of(head), 200);
  EXPECT_EQ(header_value(head, "Content-Length"), std::to_string(expected->bytes.size()));
  EXPECT_TRUE(body_of(head).empty());
  EXPECT_EQ(
      status_of(send_and_read(port, request("GET", "/api/v1/missions/999/export?format=mcap"))),
      404);
}

// Regression: invalid UTF-8 in a path or query was a 500 with nlohmann's text. No route has
// such a path: 404.
TEST_F(StationHttpTest, InvalidUtf8InAPathIs404) {
  for (const std::string target : {"/api/v1/%ff", "/api/v1/vehicles/%ff%fe",
                                   "/api/v1/vehicles/%c0%af/ckt", "/api/v1/missions/%ed%a0%80"}) {
    const auto raw = send_and_read(port, request("GET", target));
    EXPECT_EQ(status_of(raw), 404) << target << "\n" << raw;
    EXPECT_EQ(header_value(raw, "Content-Type"), "application/problem+json") << target;
    const auto problem = json::parse(body_of(raw), nullptr, false);
    ASSERT_TRUE(problem.is_object()) << raw;
    EXPECT_EQ(problem["status"], 404) << raw;
  }
}

// In a query: 400, naming the parameter.
TEST_F(StationHttpTest, InvalidUtf8InAQueryIsA400NamingTheParameter) {
  for (const auto& [target, named] : std::vector<std::pair<std::string, std::string>>{
           {"/api/v1/turns?limit=%ff", "'limit'"},
           {"/api/v1/vehicles/sim-usim/predict?speed=%ff&dheading=40", "'speed'"}}) {
    const auto raw = send_and_read(port, request("GET", target));
    EXPECT_EQ(status_of(raw), 400) << target << "\n" << raw;
    EXPECT_EQ(header_value(raw, "Content-Type"), "application/problem+json") << target;
    const auto problem = json::parse(body_of(raw), nullptr, false);
    ASSERT_TRUE(problem.is_object()) << raw;
    EXPECT_NE(problem["detail"].get<std::string>().find(named), std::string::npos) << raw;
    EXPECT_EQ(raw.find("json.exception"), std::string::npos) << target;
  }
}

}  // namespace
