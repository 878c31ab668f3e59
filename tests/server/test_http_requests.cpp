// The HTTP transport's handling of requests on loopback: decoding, keep-alive, what the Api
// answers passed through, and malformed, oversized, slow and vanishing clients.
#include <gtest/gtest.h>

#include "server/http_server_fixture.hpp"

namespace {

using namespace avk::testing::http_transport;

// --- REST ----------------------------------------------------------------------------------

TEST_F(HttpServerTest, DecodesPathAndQueryAndKeepsTheConnection) {
  start();
  HttpClient client(port);
  auto res = client.request(http::verb::get, "/api/v1/echo/a%20b?x=1&y=%2F&y=2&z=a+b%2Bc", "",
                            {{"Accept", "text/csv"}, {"Authorization", "Bearer t0k"}});
  ASSERT_EQ(res.result_int(), 200);
  EXPECT_EQ(res[http::field::content_type], "application/json");
  EXPECT_TRUE(res.keep_alive());
  const auto echo = json::parse(res.body());
  EXPECT_EQ(echo["method"], "GET");
  EXPECT_EQ(echo["path"], "/api/v1/echo/a b");
  EXPECT_EQ(echo["query"]["x"], "1");
  EXPECT_EQ(echo["query"]["y"], "2");  // the last one
  EXPECT_EQ(echo["query"]["z"], "a b+c");
  EXPECT_EQ(echo["multi_query"], json::parse(R"([["x","1"],["y","/"],["y","2"],["z","a b+c"]])"));
  EXPECT_EQ(echo["accept"], "text/csv");
  EXPECT_EQ(echo["authorization"], "Bearer t0k");
  EXPECT_EQ(echo["host"], "127.0.0.1:" + std::to_string(port));
  EXPECT_EQ(echo["remote_address"], "127.0.0.1");
  EXPECT_EQ(echo["remote_is_loopback"], true);

  // The same connection again, with a body this time.
  res = client.request(http::verb::post, "/api/v1/missions", R"({"a":1})",
                       {{"Content-Type", "application/json; charset=utf-8"}});
  ASSERT_EQ(res.result_int(), 200);
  const auto echo2 = json::parse(res.body());
  EXPECT_EQ(echo2["method"], "POST");
  EXPECT_EQ(echo2["body"], R"({"a":1})");
  EXPECT_EQ(echo2["content_type"], "application/json; charset=utf-8");
  EXPECT_EQ(api.calls.load(), 2);
}

TEST_F(HttpServerTest, Http10WithoutKeepAliveIsClosed) {
  start();
  HttpClient client(port);
  const auto res = client.request(http::verb::get, "/api/v1/echo", "", {}, 10);
  EXPECT_EQ(res.result_int(), 200);
  EXPECT_FALSE(res.keep_alive());
  EXPECT_TRUE(client.closed_by_server());
}

TEST_F(HttpServerTest, StatusAndExtraHeadersPassThrough) {
  start();
  const auto res = get(port, "/api/v1/status/201");
  EXPECT_EQ(res.result_int(), 201);
  EXPECT_EQ(res[http::field::location], "/api/v1/things/1");
  EXPECT_EQ(res[http::field::content_length], std::to_string(res.body().size()));
}

TEST_F(HttpServerTest, ExceptionInTheApiIs500ProblemJsonAndTheServerGoesOn) {
  start();
  HttpClient client(port);
  const auto res = client.request(http::verb::get, "/api/v1/throw");
  EXPECT_EQ(res.result_int(), 500);
  EXPECT_EQ(res[http::field::content_type], "application/problem+json");
  const auto problem = json::parse(res.body());
  EXPECT_EQ(problem["type"], "about:blank");
  EXPECT_EQ(problem["title"], "Internal Server Error");
  EXPECT_EQ(problem["status"], 500);
  // The exception's own words stay in the server's log.
  EXPECT_EQ(problem["detail"], "internal error (see the server log)");
  EXPECT_EQ(res.body().find("boom"), std::string::npos);
  // Same connection, and a fresh one.
  EXPECT_EQ(client.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(HttpServerTest, StreamPathWithoutUpgradeIs426) {
  start();
  const auto res = get(port, "/api/v1/stream");
  EXPECT_EQ(res.result_int(), 426);
  EXPECT_EQ(api.calls.load(), 0);
}

// --- malformed, oversized, slow and vanishing clients ----------------------------------------

TEST_F(HttpServerTest, BodyOverTheLimitIs413AndClosed) {
  HttpServerOptions o;
  o.body_limit = 1024;
  start(o);
  const std::string body(2000, 'x');
  {
    HttpClient client(port);
    const auto res = client.request(http::verb::post, "/api/v1/missions", body,
                                    {{"Content-Type", "application/json"}});
    EXPECT_EQ(res.result_int(), 413);
    EXPECT_EQ(res[http::field::content_type], "application/problem+json");
    EXPECT_TRUE(client.closed_by_server());
  }
  // The larger limit the API gives a route.
  const auto ok = HttpClient(port).request(http::verb::post, "/api/v1/large", body,
                                           {{"Content-Type", "application/json"}});
  EXPECT_EQ(ok.result_int(), 200);
  EXPECT_EQ(json::parse(ok.body())["body"], body);
  // A chunked body, whose size the header does not give.
  const std::string chunked =
      "POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\n"
      "800\r\n" +
      std::string(0x800, 'y') + "\r\n0\r\n\r\n";
  const auto raw = raw_exchange(port, chunked);
  EXPECT_EQ(status_of(raw.data), 413) << raw.data;
  EXPECT_TRUE(raw.closed());
  EXPECT_EQ(api.calls.load(), 1);
}

TEST_F(HttpServerTest, ExpectContinueGetsContinue) {
  start();
  RawClient c(port);
  c.send(
      "POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 5\r\n"
      "Expect: 100-continue\r\nConnection: close\r\n\r\n");
  // Nothing but the 100 comes before the body is sent; read it with a short deadline.
  auto first = c.read_until_closed(3000ms);
  EXPECT_TRUE(first.data.starts_with("HTTP/1.1 100 Continue")) << first.data;
}

TEST_F(HttpServerTest, HeaderOverTheLimitIs431) {
  HttpServerOptions o;
  o.header_limit = 1024;
  start(o);
  const auto raw = raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: " +
                                          std::string(4000, 'b') + "\r\n\r\n");
  EXPECT_EQ(status_of(raw.data), 431) << raw.data;
  EXPECT_TRUE(raw.closed());
  EXPECT_EQ(api.calls.load(), 0);
}

TEST_F(HttpServerTest, GarbageRequestLineIs400AndClosed) {
  start();
  const auto raw = raw_exchange(port, "HELLO\r\n\r\n");
  EXPECT_EQ(status_of(raw.data), 400) << raw.data;
  EXPECT_NE(raw.data.find("application/problem+json"), std::string::npos);
  EXPECT_TRUE(raw.closed());
  const auto bad_header = raw_exchange(port, "GET / HTTP/1.1\r\nNo colon here\r\n\r\n");
  EXPECT_EQ(status_of(bad_header.data), 400) << bad_header.data;
  EXPECT_TRUE(bad_header.closed());
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

TEST_F(HttpServerTest, ClientThatStallsInTheHeaderIsDisconnected) {
  HttpServerOptions o;
  o.header_timeout = 200ms;
  start(o);
  RawClient slow(port);
  slow.send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n");  // and nothing more
  const auto r = slow.read_until_closed(20000ms);
  EXPECT_TRUE(r.closed()) << r.ec.message();
  EXPECT_TRUE(r.data.empty());
  // A connection that sends nothing at all goes the same way.
  RawClient silent(port);
  EXPECT_TRUE(silent.read_until_closed(20000ms).closed());
  EXPECT_EQ(api.calls.load(), 0);
}

// The other side of the header timeout, without measuring time: a header that arrives in pieces,
// with other requests answered in between, is answered once it is complete.
TEST_F(HttpServerTest, HeaderSentInPiecesWithinTheTimeoutIsAnswered) {
  HttpServerOptions o;
  o.header_timeout = 60000ms;
  start(o);
  RawClient pieces(port);
  pieces.send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n");
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  pieces.send("Connection: close\r\n\r\n");
  const auto r = pieces.read_until_closed(20000ms);
  EXPECT_EQ(status_of(r.data), 200) << r.data;
  EXPECT_EQ(api.calls.load(), 4);
}

TEST_F(HttpServerTest, IdleKeepAliveConnectionIsClosedAfterIdleTimeout) {
  HttpServerOptions o;
  o.idle_timeout = 200ms;
  start(o);
  HttpClient client(port);
  EXPECT_EQ(client.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(client.closed_by_server(20000ms));
}

TEST_F(HttpServerTest, ClientVanishingMidBodyDoesNotDisturbOthers) {
  start();
  std::vector<std::unique_ptr<RawClient>> open;
  for (int i = 0; i < 5; ++i) {
    auto c = std::make_unique<RawClient>(port);
    c->send("POST /api/v1/missions HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100000\r\n\r\n" +
            std::string(1000, 'z'));
    if (i % 2 == 0)
      c->close();  // gone mid-body
    else
      open.push_back(std::move(c));  // still there, mid-body
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_EQ(api.calls.load(), 3);
}

}  // namespace
