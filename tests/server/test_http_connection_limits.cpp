// The transport's bounds on connections: the request deadline against trickled bodies, the caps
// per address and in all and which connection makes room, and the cap on live sessions.
#include <gtest/gtest.h>

#include "server/http_server_fixture.hpp"

namespace {

using namespace avk::testing::http_transport;

// A plain POSIX socket: trickles bytes while watching for the server's close.
class TrickleClient {
 public:
  explicit TrickleClient(unsigned short port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
      throw std::runtime_error("connect");
  }
  ~TrickleClient() { ::close(fd_); }
  bool send(std::string_view bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) ==
           static_cast<ssize_t>(bytes.size());
  }
  // Whether the server closed within wait (reset, or EOF after whatever it answered).
  bool closed_within(std::chrono::milliseconds wait) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) return false;
    char b[512];
    for (;;) {
      const auto n = ::recv(fd_, b, sizeof b, MSG_DONTWAIT);
      if (n == 0) return true;
      if (n < 0) return errno != EAGAIN && errno != EWOULDBLOCK;
    }
  }

 private:
  int fd_;
};

// Regression: a body sent one byte per pause shorter than the idle timeout was never
// cut. Now the whole request has a deadline.
TEST_F(HttpServerTest, ABodyTrickledInIsCutAtTheRequestDeadline) {
  HttpServerOptions o;
  o.request_timeout = 300ms;
  o.idle_timeout = 30s;
  start(o);
  TrickleClient c(port);
  ASSERT_TRUE(
      c.send("POST /api/v1/x HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100000\r\n\r\n"));
  bool closed = false;
  // 100 ms between bytes, far under the idle timeout; at most 60 s in all.
  for (int i = 0; i < 600 && !closed; ++i) {
    if (!c.send("z")) break;
    closed = c.closed_within(100ms);
  }
  EXPECT_TRUE(closed);
  EXPECT_EQ(api.calls.load(), 0);
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
}

// Connections from one address that have sent a request are bounded: at the cap the oldest one
// idle between requests makes room for the new one's request.
TEST_F(HttpServerTest, AtThePerAddressCapTheOldestIdleConnectionMakesRoom) {
  HttpServerOptions o;
  o.max_connections_per_address = 4;
  start(o);
  std::vector<std::unique_ptr<HttpClient>> idle;
  for (int i = 0; i < 4; ++i) {
    idle.push_back(std::make_unique<HttpClient>(port));
    ASSERT_EQ(idle.back()->request(http::verb::get, "/api/v1/echo").result_int(), 200);
  }
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(idle[0]->closed_by_server());
  EXPECT_EQ(idle[3]->request(http::verb::get, "/api/v1/echo").result_int(), 200);
}

// Regression: the per-address cap counted connections that had not sent their request yet, so a
// burst of connections from one address (dashboards behind a proxy) closed its own members
// before they asked. Those are bounded by the header timeout instead.
TEST_F(HttpServerTest, ConnectionsThatHaveNotAskedYetAreNotCutByThePerAddressCap) {
  HttpServerOptions o;
  o.max_connections_per_address = 4;
  start(o);
  std::vector<std::unique_ptr<RawClient>> waiting;
  for (int i = 0; i < 12; ++i)
    waiting.push_back(std::make_unique<RawClient>(port));
  for (auto& c : waiting) {
    c->send("GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(status_of(c->read_until_closed().data), 200);
  }
}

// Regression: with every slot taken, the oldest waiting connection of any address made room, so
// one address's flood of slow connections closed another client's. The address holding the
// most connections makes room now.
TEST_F(HttpServerTest, AtTheTotalCapTheAddressHoldingTheMostMakesRoom) {
  HttpServerOptions o;
  o.max_connections = 6;
  start(o);
  HttpClient other(port, "127.0.0.2");
  ASSERT_EQ(other.request(http::verb::get, "/api/v1/echo").result_int(), 200);
  std::vector<std::unique_ptr<TrickleClient>> slow;
  for (int i = 0; i < 5; ++i) {
    slow.push_back(std::make_unique<TrickleClient>(port));
    slow.back()->send("GET /api/v1/echo HTTP/1.1\r\n");  // and never the rest
  }
  // Full (6): this connection makes the oldest of 127.0.0.1's slow ones close, not 127.0.0.2's
  // older idle one.
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  EXPECT_TRUE(slow[0]->closed_within(20000ms));
  EXPECT_EQ(other.request(http::verb::get, "/api/v1/echo").result_int(), 200);
}

// When no connection can make room (open streams), a new one gets a 503, not a silent hang.
TEST_F(HttpServerTest, OverTheTotalCapWithNothingToCloseIs503) {
  HttpServerOptions o;
  o.max_connections = 2;
  start(o);
  WsClient a(port);
  ASSERT_FALSE(a.handshake_error());
  ASSERT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
  WsClient b(port);
  ASSERT_FALSE(b.handshake_error());
  ASSERT_TRUE(wait_for([&] { return server->open_stream_sessions() == 2; }));
  const auto refused = raw_exchange(port, "GET /api/v1/echo HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(status_of(refused.data), 503) << refused.data;
  EXPECT_NE(refused.data.find("application/problem+json"), std::string::npos);
  EXPECT_TRUE(refused.closed());
  EXPECT_EQ(api.calls.load(), 0);
}

// Regression: a burst of 100 WebSocket clients from one address lost 36: the per-address cap of
// 64 counted the connections whose upgrade had not been read yet and closed them to make room.
TEST_F(HttpServerTest, ABurstOfUpgradesFromOneAddressAllGetSessions) {
  start();
  constexpr int kClients = 100;
  net::io_context ioc;
  std::vector<std::unique_ptr<websocket::stream<beast::tcp_stream>>> clients;
  std::atomic<int> opened{0};
  std::atomic<int> failed{0};
  for (int i = 0; i < kClients; ++i) {
    clients.push_back(std::make_unique<websocket::stream<beast::tcp_stream>>(ioc));
    auto& ws = *clients.back();
    beast::get_lowest_layer(ws).async_connect(loopback(port), [&ws, &opened, &failed,
                                                               this](beast::error_code ec) {
      if (ec) return void(++failed);
      ws.async_handshake("127.0.0.1:" + std::to_string(port), "/api/v1/stream",
                         [&opened, &failed](beast::error_code hec) { ++(hec ? failed : opened); });
    });
  }
  ioc.run_for(30s);
  EXPECT_EQ(opened.load(), kClients);
  EXPECT_EQ(failed.load(), 0);
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == kClients; }, 20000ms))
      << server->open_stream_sessions();
}

// Live sessions from one address have a cap of their own: one over it is a 503 with
// Retry-After, and a place that frees up is taken again.
TEST_F(HttpServerTest, LiveSessionsPerAddressAreCappedWith503AndRetryAfter) {
  HttpServerOptions o;
  o.max_streams_per_address = 2;
  start(o);
  auto a = std::make_unique<WsClient>(port);
  ASSERT_FALSE(a->handshake_error());
  WsClient b(port, "", 0, "/api/v1/foxglove", "foxglove.websocket.v1");
  ASSERT_FALSE(b.handshake_error());
  WsClient over(port);
  EXPECT_TRUE(over.handshake_error());
  EXPECT_EQ(over.handshake_response().result_int(), 503);
  EXPECT_FALSE(over.handshake_response()[http::field::retry_after].empty());
  // The server counts a session once its handshake's answer is written, which the client may
  // see first: wait for the count, do not race it.
  for (const auto deadline = Clock::now() + 20s;
       server->open_stream_sessions() != 2u && Clock::now() < deadline;)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(server->open_stream_sessions(), 2u);
  a.reset();
  bool reopened = false;
  for (const auto deadline = Clock::now() + 20s; !reopened && Clock::now() < deadline;) {
    WsClient again(port);
    reopened = !again.handshake_error();
    if (!reopened) std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(reopened);
}

}  // namespace
