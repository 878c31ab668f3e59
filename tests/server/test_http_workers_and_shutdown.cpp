// Request work on the request workers (a busy pool, expensive requests in all and per address)
// and the server's lifecycle: stop, destruction with open connections, and a port taken.
#include <gtest/gtest.h>

#include "server/http_server_fixture.hpp"

namespace {

using namespace avk::testing::http_transport;

// --- lifecycle -----------------------------------------------------------------------------

TEST_F(HttpServerTest, StopClosesStreamsWithGoingAway) {
  start();
  WsClient a(port);
  WsClient b(port);
  ASSERT_TRUE(a.read());
  ASSERT_TRUE(b.read());
  HttpClient idle(port);
  EXPECT_EQ(idle.request(http::verb::get, "/api/v1/echo").result_int(), 200);

  // A hang here fails by the test's own time limit; nothing below measures time.
  std::thread stopper([&] { server->stop(); });
  EXPECT_FALSE(a.read());
  EXPECT_EQ(a.error(), websocket::error::closed);
  EXPECT_EQ(a.close_reason().code, websocket::close_code::going_away);
  EXPECT_FALSE(b.read());
  EXPECT_EQ(b.close_reason().code, websocket::close_code::going_away);
  stopper.join();
  EXPECT_TRUE(idle.closed_by_server(20000ms));
  EXPECT_EQ(server->open_stream_sessions(), 0u);
  server->stop();                                      // idempotent
  EXPECT_THROW(RawClient{port}, beast::system_error);  // no longer accepting
}

TEST_F(HttpServerTest, DestructionWithOpenConnectionsNeitherHangsNorCrashes) {
  HttpServerOptions o;
  o.close_timeout = 300ms;
  start(o);
  // A stream client that stopped reading with a write stuck in the socket, a half header,
  // a half body and an idle keep-alive connection.
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(stalled.read());
  const std::string pad(64 * 1024, 'q');
  for (int i = 0; i < 100; ++i)
    hub.publish("turn", 0.0, R"({"pad":")" + pad + R"("})");
  RawClient half_header(port);
  half_header.send("GET / HTTP/1.1\r\nHost");
  RawClient half_body(port);
  half_body.send("POST /api/v1/x HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 10\r\n\r\nab");
  HttpClient idle(port);
  EXPECT_EQ(idle.request(http::verb::get, "/api/v1/echo").result_int(), 200);

  std::atomic<bool> publishing{true};
  std::thread publisher([&] {
    // A publisher that keeps going while the server goes away must not touch a dead session.
    while (publishing) {
      hub.publish("turn", 0.0, "{}");
      hub.publish("nav", 0.0, "{}");
      std::this_thread::sleep_for(100us);
    }
  });
  server.reset();  // returns (within close_timeout): a hang fails by the test's time limit
  std::this_thread::sleep_for(20ms);
  publishing = false;
  publisher.join();
  EXPECT_TRUE(half_header.read_until_closed(20000ms).closed());
}

TEST_F(HttpServerTest, StartThenStopWithoutClients) {
  start();
  server->stop();
  server.reset();
  HttpServer never_started(HttpServerOptions{}, api, hub);
  EXPECT_EQ(never_started.port(), 0);
}

TEST_F(HttpServerTest, BindFailureNamesTheAddress) {
  start();
  HttpServerOptions o;
  o.port = port;
  HttpServer second(o, api, hub);
  try {
    second.start();
    FAIL() << "a second server bound the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos)
        << e.what();
  }
  HttpServerOptions bad;
  bad.bind_address = "not-an-address";
  EXPECT_THROW(HttpServer(bad, api, hub).start(), std::runtime_error);
}

// --- request work on the request workers ---------------------------------------------------

std::string raw_get(const std::string& target) {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
}

bool has_header(const std::string& raw, const std::string& line) {
  return raw.find("\r\n" + line + "\r\n") != std::string::npos;
}

// Regression: request work ran on the two I/O threads, so two slow requests stalled /health and
// the live stream. It runs on the request workers; with the only worker busy and the queue full,
// the next request is a 503 with Retry-After while /health and the stream still answer.
TEST_F(HttpServerTest, ABusyPoolAnswers503WhileHealthAndTheStreamAnswer) {
  HttpServerOptions o;
  o.request_workers = 1;
  o.request_queue = 1;
  start(o);
  const auto [first, second] = the_worker_busy_and_one_waiting(port);
  ASSERT_TRUE(first && second);

  const auto refused = raw_exchange(port, raw_get("/api/v1/echo"));
  EXPECT_EQ(status_of(refused.data), 503) << refused.data;
  EXPECT_TRUE(has_header(refused.data, "Retry-After: 1")) << refused.data;
  EXPECT_NE(refused.data.find("application/problem+json"), std::string::npos);

  EXPECT_EQ(get(port, "/api/v1/health").result_int(), 200);
  WsClient ws(port);
  ASSERT_FALSE(ws.handshake_error());
  ASSERT_TRUE(ws.read());  // hello
  ws.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(ws.read());  // subscribed
  hub.publish("turn", 1.0, R"({"id":1})");
  const auto message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["data"]["id"], 1);

  api.open_gate();
  EXPECT_EQ(status_of(first->read_until_closed().data), 200);
  EXPECT_EQ(status_of(second->read_until_closed().data), 200);
}

// Expensive requests run on at most expensive_requests workers, the others stay for cheap ones,
// and one client address may have expensive_requests_per_address of them running or waiting.
TEST_F(HttpServerTest, ExpensiveRequestsAreLimitedInAllAndPerAddress) {
  HttpServerOptions o;
  o.request_workers = 2;
  o.expensive_requests = 1;
  o.expensive_requests_per_address = 1;
  start(o);
  RawClient heavy(port);
  heavy.send(raw_get("/api/v1/block?cost=expensive"));
  ASSERT_TRUE(wait_for([&] { return api.blocked.load() == 1; }));

  const auto same_address = raw_exchange(port, raw_get("/api/v1/echo?cost=expensive"));
  EXPECT_EQ(status_of(same_address.data), 429) << same_address.data;
  EXPECT_TRUE(has_header(same_address.data, "Retry-After: 1")) << same_address.data;

  // Another address is let in, and waits for the expensive worker.
  HttpClient other(port, "127.0.0.2");
  std::optional<http::response<http::string_body>> other_answer;
  std::thread asking(
      [&] { other_answer = other.request(http::verb::get, "/api/v1/echo?cost=expensive"); });
  EXPECT_TRUE(wait_for([&] { return server->waiting_requests() == 1; }));
  // Cheap work takes the other worker meanwhile.
  EXPECT_EQ(get(port, "/api/v1/echo").result_int(), 200);
  api.open_gate();
  asking.join();
  ASSERT_TRUE(other_answer);
  EXPECT_EQ(other_answer->result_int(), 200);
  EXPECT_EQ(status_of(heavy.read_until_closed().data), 200);
  // Answered: the address has its share back.
  EXPECT_EQ(get(port, "/api/v1/echo?cost=expensive").result_int(), 200);
}

// A request still waiting for a worker when the server stops is answered 503 at once, not left
// to the stop's deadline.
TEST_F(HttpServerTest, StopAnswersTheRequestsStillWaiting) {
  HttpServerOptions o;
  o.request_workers = 1;
  start(o);
  const auto [first, waiting] = the_worker_busy_and_one_waiting(port);
  ASSERT_TRUE(first && waiting);
  std::thread stopping([&] { server->stop(); });
  const auto answer = waiting->read_until_closed();
  EXPECT_EQ(status_of(answer.data), 503) << answer.data;
  EXPECT_NE(answer.data.find("shutting down"), std::string::npos);
  api.open_gate();
  stopping.join();
}

}  // namespace
