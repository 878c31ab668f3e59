// The live connections over WebSocket: the stream's protocol and Origin rule, the Foxglove
// subprotocol, and the slow-client policy of both (events close, telemetry keeps the newest).
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <vector>

#include "server/http_server_fixture.hpp"

namespace {

using namespace avk::testing::http_transport;

// --- the stream ----------------------------------------------------------------------------

TEST_F(HttpServerTest, StreamHelloSubscribeAndPublish) {
  start();
  WsClient ws(port);
  ASSERT_FALSE(ws.handshake_error()) << ws.handshake_error().message();
  const auto hello = ws.read();
  ASSERT_TRUE(hello);
  EXPECT_EQ((*hello)["type"], "hello");
  EXPECT_EQ((*hello)["session_id"], hub.session_id());
  EXPECT_EQ((*hello)["server_version"], "test-1");
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));

  ws.send(R"({"subscribe":["turn"]})");
  auto reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ(*reply, json::parse(R"({"type":"subscribed","topics":["turn"],"max_hz":0})"));
  EXPECT_EQ(hub.subscriber_count("turn"), 1u);

  hub.publish("turn", 12.5, R"({"event":"finished","id":7})");
  auto message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["topic"], "turn");
  EXPECT_EQ((*message)["seq"], 1);
  EXPECT_EQ((*message)["t"], 12.5);
  EXPECT_EQ((*message)["data"]["id"], 7);

  // Errors are answered and the connection stays.
  ws.send(R"({"subscribe":["turn","bogus"]})");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");
  EXPECT_NE((*reply)["message"].get<std::string>().find("bogus"), std::string::npos);
  ws.send("not json");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");
  ws.send("\x01\x02", true);
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["type"], "error");

  ws.send(R"({"subscribe":["nav"],"unsubscribe":["turn"]})");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ(*reply, json::parse(R"({"type":"subscribed","topics":["nav"],"max_hz":0})"));
  EXPECT_EQ(hub.subscriber_count("turn"), 0u);
  hub.publish("turn", 13.0, "{}");  // no longer subscribed
  hub.publish("nav", 13.0, R"({"x":1})");
  message = ws.read();
  ASSERT_TRUE(message);
  EXPECT_EQ((*message)["topic"], "nav");
  EXPECT_EQ(server->open_stream_sessions(), 1u);
}

TEST_F(HttpServerTest, StreamChecksOrigin) {
  start();
  WsClient foreign(port, "http://evil.example");
  EXPECT_EQ(foreign.handshake_error(), websocket::error::upgrade_declined);
  EXPECT_EQ(foreign.handshake_response().result_int(), 403);
  WsClient other_port(port, "http://127.0.0.1:1");
  EXPECT_EQ(other_port.handshake_response().result_int(), 403);

  WsClient same(port, "http://127.0.0.1:" + std::to_string(port));
  ASSERT_FALSE(same.handshake_error()) << same.handshake_error().message();
  EXPECT_TRUE(same.read());
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
}

// One client stops reading: it is closed with 1008 once its event queue overflows, while a
// reading client gets every message in order and the publisher never waits.
TEST_F(HttpServerTest, StalledEventClientIsClosedAndOthersKeepUp) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  // The close frame waits behind the write the stalled client blocks; give the test time to
  // come back and read it (the default cuts such a client after 5 s).
  o.close_timeout = 30s;
  start(o);
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(stalled.read());

  constexpr int kMessages = 2000;
  constexpr int kWindow = 4;  // below the queue limit: the reader is never the one too slow
  std::mutex mutex;
  std::condition_variable received_cv;
  int received = 0;
  bool reader_ok = true;
  std::string reader_failure;

  WsClient reader(port);
  ASSERT_TRUE(reader.read());
  reader.send(R"({"subscribe":["turn"]})");
  ASSERT_TRUE(reader.read());
  std::thread reader_thread([&] {
    for (int i = 1; i <= kMessages; ++i) {
      const auto m = reader.read(10000ms);
      std::lock_guard lock(mutex);
      if (!m || (*m)["seq"] != i || (*m)["data"]["i"] != i) {
        reader_ok = false;
        reader_failure = m ? "got seq " + (*m)["seq"].dump() + " for " + std::to_string(i)
                           : "read failed: " + reader.error().message();
        received_cv.notify_all();
        return;
      }
      received = i;
      received_cv.notify_all();
    }
  });

  const std::string pad(64 * 1024, 'p');
  for (int i = 1; i <= kMessages; ++i) {
    {
      std::unique_lock lock(mutex);
      const bool ok =
          received_cv.wait_for(lock, 10s, [&] { return !reader_ok || received >= i - kWindow; });
      if (!ok || !reader_ok) break;
    }
    const std::string data = R"({"i":)" + std::to_string(i) + R"(,"pad":")" + pad + R"("})";
    hub.publish("turn", i * 0.1, data);
  }
  reader_thread.join();
  EXPECT_TRUE(reader_ok) << reader_failure;
  EXPECT_EQ(received, kMessages);
  // That the publisher never waited is the loop finishing with a client that never reads; how
  // long a publish takes is bench/stream_load's to measure.

  // The stalled session is gone from the hub and the open count; it still has its close frame
  // to deliver behind what the socket holds.
  EXPECT_TRUE(wait_for([&] { return hub.subscriber_count("turn") == 1; }));
  EXPECT_TRUE(wait_for([&] { return server->open_stream_sessions() == 1; }));
  int stalled_got = 0;
  std::int64_t last_seq = 0;
  while (auto m = stalled.read()) {
    ++stalled_got;
    ASSERT_GT((*m)["seq"].get<std::int64_t>(), last_seq);
    last_seq = (*m)["seq"].get<std::int64_t>();
  }
  EXPECT_EQ(stalled.error(), websocket::error::closed) << stalled.error().message();
  EXPECT_EQ(stalled.close_reason().code, websocket::close_code::policy_error);
  const auto& reason = stalled.close_reason().reason;
  EXPECT_EQ(std::string(reason.data(), reason.size()), "too slow: re-sync over REST");
  EXPECT_LT(stalled_got, kMessages);
}

// Telemetry is latest-value-wins: a client that stops reading nav accumulates nothing and is
// not closed; when it reads again the newest sample reaches it.
TEST_F(HttpServerTest, StalledTelemetryClientStaysOpen) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  start(o);
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["nav"]})");
  ASSERT_TRUE(stalled.read());

  constexpr int kMessages = 2000;
  const std::string pad(64 * 1024, 'n');
  // Returns although the client reads nothing: publish never waits for a session.
  for (int i = 1; i <= kMessages; ++i)
    hub.publish("nav", i * 0.1, R"({"i":)" + std::to_string(i) + R"(,"pad":")" + pad + R"("})");

  std::this_thread::sleep_for(200ms);  // let the session work through what was posted
  EXPECT_EQ(server->open_stream_sessions(), 1u);
  EXPECT_EQ(hub.subscriber_count("nav"), 1u);

  int got = 0;
  std::int64_t last_seq = 0;
  while (last_seq < kMessages) {
    const auto m = stalled.read();
    ASSERT_TRUE(m) << stalled.error().message();
    ++got;
    ASSERT_GT((*m)["seq"].get<std::int64_t>(), last_seq);
    last_seq = (*m)["seq"].get<std::int64_t>();
  }
  EXPECT_EQ(last_seq, kMessages);
  EXPECT_LT(got, kMessages);  // older frames were replaced, not queued
  EXPECT_EQ(server->open_stream_sessions(), 1u);
}

// A fleet's telemetry: a stalled client's unsent nav of one vehicle is replaced by that vehicle's
// newer nav only, never by another vehicle's, so each vehicle's newest sample reaches it.
TEST_F(HttpServerTest, StalledTelemetryKeepsEachVehiclesNewestSample) {
  start({});
  WsClient stalled(port, "", 4096);
  ASSERT_TRUE(stalled.read());
  stalled.send(R"({"subscribe":["nav"]})");
  ASSERT_TRUE(stalled.read());

  constexpr int kMessages = 2000;  // alternately vehicle a (odd i) and vehicle b (even i)
  const std::string pad(64 * 1024, 'n');
  for (int i = 1; i <= kMessages; ++i) {
    const std::string vid = i % 2 ? "a" : "b";
    hub.publish("nav", i * 0.1,
                R"({"vehicle_id":")" + vid + R"(","i":)" + std::to_string(i) + R"(,"pad":")" + pad +
                    R"("})",
                vid);
  }
  // Until both vehicles' newest samples have come (their slots may be in either order); a
  // sample replaced by the other vehicle's would never come, and the read would time out.
  std::map<std::string, int> newest;
  int got = 0;
  while (newest["a"] != kMessages - 1 || newest["b"] != kMessages) {
    const auto m = stalled.read();
    ASSERT_TRUE(m) << stalled.error().message() << "; newest a " << newest["a"] << ", b "
                   << newest["b"];
    ++got;
    newest[(*m)["data"]["vehicle_id"].get<std::string>()] = (*m)["data"]["i"].get<int>();
  }
  EXPECT_LT(got, kMessages);  // older frames were replaced
}

// max_hz: a client asks for fewer nav and helm frames a second per vehicle. Frames published
// within 1/max_hz of a vehicle's last taken one are not taken; each vehicle's first one is;
// events are never held back. Bad values are refused and leave the session as it was.
TEST_F(HttpServerTest, MaxHzThinsEachVehiclesTelemetry) {
  start({});
  WsClient ws(port);
  ASSERT_TRUE(ws.read());  // hello
  ws.send(R"({"subscribe":["nav","turn"],"max_hz":2})");
  auto reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["max_hz"], 2.0);
  for (const char* bad : {R"({"max_hz":-1})", R"({"max_hz":"fast"})", R"({"max_hz":5000})"}) {
    ws.send(bad);
    reply = ws.read();
    ASSERT_TRUE(reply);
    EXPECT_EQ((*reply)["type"], "error") << bad;
    EXPECT_NE((*reply)["message"].get<std::string>().find("max_hz"), std::string::npos);
  }

  constexpr int kMessages = 400;  // alternately vehicle a and vehicle b
  const auto begin = std::chrono::steady_clock::now();
  for (int i = 1; i <= kMessages; ++i) {
    const std::string vid = i % 2 ? "a" : "b";
    hub.publish("nav", i * 0.01, R"({"vehicle_id":")" + vid + R"(","i":)" + std::to_string(i) + "}",
                vid);
  }
  const double published_over_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  hub.publish("turn", 99.0, R"({"event":"marker"})");  // an event: after every nav taken
  std::map<std::string, std::vector<int>> got;
  for (;;) {
    const auto m = ws.read();
    ASSERT_TRUE(m) << ws.error().message();
    if ((*m)["topic"] == "turn") break;
    got[(*m)["data"]["vehicle_id"].get<std::string>()].push_back((*m)["data"]["i"].get<int>());
  }
  ASSERT_FALSE(got["a"].empty() || got["b"].empty()) << "each vehicle's first is taken";
  EXPECT_EQ(got["a"].front(), 1);
  EXPECT_EQ(got["b"].front(), 2);
  // At 2 a second per vehicle: the first, and one more per half second the publishing took.
  const auto most = static_cast<std::size_t>(1 + published_over_s * 2.0 + 1);
  EXPECT_LE(got["a"].size(), most);
  EXPECT_LE(got["b"].size(), most);

  // 0 lifts the limit: a vehicle's next frame goes out at once.
  ws.send(R"({"max_hz":0})");
  reply = ws.read();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["max_hz"], 0.0);
  hub.publish("nav", 5.0, R"({"vehicle_id":"a","i":1000})", "a");
  const auto m = ws.read();
  ASSERT_TRUE(m);
  EXPECT_EQ((*m)["data"]["i"], 1000);
}

// --- the Foxglove connection ---------------------------------------------------------------

// A Foxglove client (foxglove.websocket.v1) on the given path, past server info and advertise.
std::unique_ptr<WsClient> foxglove_client(unsigned short port, const std::string& path,
                                          json* advertise = nullptr, int receive_buffer = 0) {
  auto c = std::make_unique<WsClient>(port, "", receive_buffer, path, "foxglove.websocket.v1");
  if (c->handshake_error()) return c;
  const auto info = c->read();
  EXPECT_TRUE(info && (*info)["op"] == "serverInfo");
  const auto adv = c->read();
  EXPECT_TRUE(adv && (*adv)["op"] == "advertise");
  if (advertise && adv) *advertise = *adv;
  return c;
}

std::uint32_t channel_id(const json& advertise, const std::string& topic) {
  for (const auto& c : advertise["channels"])
    if (c["topic"] == topic) return c["id"].get<std::uint32_t>();
  ADD_FAILURE() << topic;
  return 0;
}

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + i])) << (8 * i);
  return v;
}

TEST_F(HttpServerTest, FoxgloveSelectsItsSubprotocolAndSendsBinaryMessageData) {
  start();
  hub.foxglove().advertise("boat", avk::app::foxglove::live_channels("boat"));
  for (const std::string path : {"/api/v1/foxglove", "/api/v1/stream"}) {
    json adv;
    auto c = foxglove_client(port, path, &adv);
    ASSERT_FALSE(c->handshake_error()) << path << ": " << c->handshake_error().message();
    EXPECT_EQ(c->handshake_response()[http::field::sec_websocket_protocol],
              "foxglove.websocket.v1");
    const auto pose = channel_id(adv, "/boat/pose");
    c->send(
        json{{"op", "subscribe"}, {"subscriptions", {{{"id", 41}, {"channelId", pose}}}}}.dump());
    ASSERT_TRUE(wait_for([&] { return hub.foxglove().wanted("/boat/pose"); }));
    hub.foxglove().publish("/boat/pose", 1'500'000'000ULL, R"({"x":1})");
    const auto frame = c->read_text();
    ASSERT_TRUE(frame) << c->error().message();
    EXPECT_TRUE(c->got_binary());
    ASSERT_EQ(frame->size(), 13u + 7u);
    EXPECT_EQ(static_cast<unsigned char>((*frame)[0]), 0x01);
    EXPECT_EQ(le32(*frame, 1), 41u);
    EXPECT_EQ(le32(*frame, 5) | (std::uint64_t{le32(*frame, 9)} << 32), 1'500'000'000ULL);
    EXPECT_EQ(frame->substr(13), R"({"x":1})");
    c->send(json{{"op", "unsubscribe"}, {"subscriptionIds", {41}}}.dump());
    ASSERT_TRUE(wait_for([&] { return !hub.foxglove().wanted("/boat/pose"); }));
  }
  // Without the subprotocol the Foxglove path refuses the upgrade and says why.
  WsClient bare(port, "", 0, "/api/v1/foxglove");
  EXPECT_EQ(bare.handshake_response().result_int(), 400);
}

// The Origin rule with an operator's allow-list: Foxglove's web edition is let in only when
// named, on the Foxglove connection and the stream alike.
TEST_F(HttpServerTest, AllowedOriginsOpenTheLiveConnectionsToANamedSiteOnly) {
  HttpServerOptions o;
  o.allowed_origins = {"https://app.foxglove.dev"};
  start(o);
  WsClient fox(port, "https://App.Foxglove.dev", 0, "/api/v1/foxglove", "foxglove.websocket.v1");
  EXPECT_FALSE(fox.handshake_error()) << fox.handshake_error().message();
  WsClient stream(port, "https://app.foxglove.dev");
  EXPECT_FALSE(stream.handshake_error()) << stream.handshake_error().message();
  WsClient other(port, "https://app.foxglove.dev.evil.example", 0, "/api/v1/foxglove",
                 "foxglove.websocket.v1");
  EXPECT_EQ(other.handshake_response().result_int(), 403);
  WsClient http_scheme(port, "http://app.foxglove.dev", 0, "/api/v1/foxglove",
                       "foxglove.websocket.v1");
  EXPECT_EQ(http_scheme.handshake_response().result_int(), 403);
}

// A client that stops reading a channel of events is closed with 1008; one that stops reading
// telemetry only loses older samples.
TEST_F(HttpServerTest, FoxgloveStalledEventClientIsClosedAndTelemetryClientStaysOpen) {
  HttpServerOptions o;
  o.stream_event_queue_limit = 8;
  o.close_timeout = 30s;
  start(o);
  auto& fox = hub.foxglove();
  fox.advertise("boat", avk::app::foxglove::live_channels("boat"));
  json adv;
  auto events = foxglove_client(port, "/api/v1/foxglove", &adv, 4096);
  auto telemetry = foxglove_client(port, "/api/v1/foxglove", nullptr, 4096);
  events->send(json{{"op", "subscribe"},
                    {"subscriptions", {{{"id", 1}, {"channelId", channel_id(adv, "/boat/log")}}}}}
                   .dump());
  telemetry->send(
      json{{"op", "subscribe"},
           {"subscriptions", {{{"id", 2}, {"channelId", channel_id(adv, "/boat/pose")}}}}}
          .dump());
  ASSERT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/log") == 1; }));
  ASSERT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/pose") == 1; }));
  const std::string pad(64 * 1024, 'p');
  constexpr int kMessages = 2000;
  for (int i = 1; i <= kMessages; ++i) {
    fox.publish("/boat/log", static_cast<std::uint64_t>(i), R"({"pad":")" + pad + R"("})");
    fox.publish("/boat/pose", static_cast<std::uint64_t>(i), R"({"i":)" + std::to_string(i) + "}");
  }
  EXPECT_TRUE(wait_for([&] { return fox.subscriber_count("/boat/log") == 0; }));
  while (events->read_text()) {
  }
  EXPECT_EQ(events->close_reason().code, websocket::close_code::policy_error);
  // The telemetry client reads on and reaches the newest pose.
  int got = 0;
  for (;;) {
    const auto m = telemetry->read_text();
    ASSERT_TRUE(m) << telemetry->error().message();
    if (!telemetry->got_binary()) continue;
    ++got;
    if (m->substr(13) == R"({"i":)" + std::to_string(kMessages) + "}") break;
  }
  EXPECT_LT(got, kMessages);
  EXPECT_EQ(fox.subscriber_count("/boat/pose"), 1u);
}

}  // namespace
