// The Foxglove fan-out without sockets: channel ids, subscriptions, latched scenes, a vehicle that
// goes away and comes back; and the per-client send queue the stream and Foxglove sessions share.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "server/foxglove_hub.hpp"
#include "server/send_queue.hpp"

namespace {

using namespace avk;
using namespace avk::server;
using nlohmann::json;

struct FakeClient final : FoxgloveClient {
  std::vector<std::string> texts;
  std::vector<std::shared_ptr<const FoxgloveFrame>> frames;
  std::vector<std::uint32_t> removed;
  std::size_t times = 0;
  void send_text(std::shared_ptr<const std::string> t) override { texts.push_back(*t); }
  void deliver(std::shared_ptr<const FoxgloveFrame> f) override { frames.push_back(std::move(f)); }
  void send_time(std::uint64_t) override { ++times; }
  void channels_removed(std::vector<std::uint32_t> ids,
                        std::shared_ptr<const std::string> t) override {
    removed.insert(removed.end(), ids.begin(), ids.end());
    texts.push_back(*t);
  }
};

std::uint32_t id_of(const json& advertise, const std::string& topic) {
  for (const auto& c : advertise["channels"])
    if (c["topic"] == topic) return c["id"].get<std::uint32_t>();
  ADD_FAILURE() << "no channel " << topic << " in " << advertise.dump();
  return 0;
}

TEST(FoxgloveHub, ANewClientGetsServerInfoAndEveryAdvertisedChannel) {
  FoxgloveHub hub("abc");
  const auto info = json::parse(hub.server_info("avk-station 1"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["sessionId"], "abc");
  EXPECT_EQ(info["capabilities"], json::array({"time"}));
  auto early = std::make_shared<FakeClient>();
  // Before any vehicle: an advertise with no channels, as the protocol promises one.
  EXPECT_EQ(json::parse(hub.join(early))["channels"].size(), 0u);
  hub.advertise("boat", app::foxglove::live_channels("boat"));
  ASSERT_EQ(early->texts.size(), 1u);
  const auto adv = json::parse(early->texts[0]);
  EXPECT_EQ(adv["op"], "advertise");
  EXPECT_EQ(adv["channels"].size(), app::foxglove::live_channels("boat").size());
  for (const auto& c : adv["channels"]) {
    EXPECT_EQ(c["encoding"], "json");
    EXPECT_EQ(c["schemaEncoding"], "jsonschema");
    EXPECT_FALSE(c["schema"].get<std::string>().empty());
  }
  auto late = std::make_shared<FakeClient>();
  EXPECT_EQ(json::parse(hub.join(late))["channels"], adv["channels"]);
  EXPECT_EQ(hub.client_count(), 2u);
}

TEST(FoxgloveHub, MessagesGoOnlyToSubscribersAndOnlyWhenWanted) {
  FoxgloveHub hub("s");
  hub.advertise("boat", app::foxglove::live_channels("boat"));
  auto a = std::make_shared<FakeClient>();
  auto b = std::make_shared<FakeClient>();
  const auto adv = json::parse(hub.join(a));
  hub.join(b);
  const auto pose = id_of(adv, "/boat/pose");
  EXPECT_FALSE(hub.wanted("/boat/pose"));
  EXPECT_EQ(hub.subscribe(a.get(), pose, nullptr), FoxgloveHub::SubscribeOutcome::ok);
  EXPECT_TRUE(hub.wanted("/boat/pose"));
  EXPECT_FALSE(hub.wanted("/boat/navigation"));
  hub.publish("/boat/pose", 42, "{}");
  hub.publish("/boat/navigation", 43, "{}");  // nobody: not even built into a frame
  ASSERT_EQ(a->frames.size(), 1u);
  EXPECT_EQ(a->frames[0]->channel_id, pose);
  EXPECT_EQ(a->frames[0]->t_ns, 42u);
  EXPECT_TRUE(a->frames[0]->latest_value_wins);
  EXPECT_TRUE(b->frames.empty());
  EXPECT_EQ(hub.subscribe(b.get(), 9999, nullptr), FoxgloveHub::SubscribeOutcome::unknown_channel);
  hub.unsubscribe(a.get(), pose);
  hub.publish("/boat/pose", 44, "{}");
  EXPECT_EQ(a->frames.size(), 1u);
  // Status and time reach every client.
  hub.status(app::foxglove::LogLevel::warning, "containment");
  hub.time(5);
  const auto status = json::parse(b->texts.back());
  EXPECT_EQ(status["op"], "status");
  EXPECT_EQ(status["level"], 1);
  EXPECT_EQ(a->times, 1u);
}

TEST(FoxgloveHub, LatchedScenesReachALateSubscriberAndEventsAreNotLatestValue) {
  FoxgloveHub hub("s");
  hub.advertise("boat", app::foxglove::live_channels("boat"));
  hub.publish("/boat/region", 7, R"({"region":1})");  // no subscriber yet, but latched
  auto c = std::make_shared<FakeClient>();
  const auto adv = json::parse(hub.join(c));
  std::shared_ptr<const FoxgloveFrame> latched;
  ASSERT_EQ(hub.subscribe(c.get(), id_of(adv, "/boat/region"), &latched),
            FoxgloveHub::SubscribeOutcome::ok);
  ASSERT_TRUE(latched);
  EXPECT_EQ(*latched->payload, R"({"region":1})");
  std::shared_ptr<const FoxgloveFrame> none;
  ASSERT_EQ(hub.subscribe(c.get(), id_of(adv, "/boat/log"), &none),
            FoxgloveHub::SubscribeOutcome::ok);
  EXPECT_FALSE(none);
  hub.publish("/boat/log", 8, "{}");
  ASSERT_EQ(c->frames.size(), 1u);
  EXPECT_FALSE(c->frames[0]->latest_value_wins);
}

TEST(FoxgloveHub, AVehicleThatGoesAwayIsUnadvertisedAndComesBackWithTheSameIds) {
  FoxgloveHub hub("s");
  hub.advertise("boat", app::foxglove::live_channels("boat"));
  hub.advertise("skiff", app::foxglove::live_channels("skiff"));
  auto c = std::make_shared<FakeClient>();
  const auto adv = json::parse(hub.join(c));
  const auto pose = id_of(adv, "/boat/pose");
  ASSERT_EQ(hub.subscribe(c.get(), pose, nullptr), FoxgloveHub::SubscribeOutcome::ok);
  hub.unadvertise("boat");
  EXPECT_EQ(c->removed.size(), app::foxglove::live_channels("boat").size());
  const auto un = json::parse(c->texts.back());
  EXPECT_EQ(un["op"], "unadvertise");
  EXPECT_FALSE(hub.wanted("/boat/pose"));
  EXPECT_EQ(hub.subscribe(c.get(), pose, nullptr), FoxgloveHub::SubscribeOutcome::unknown_channel);
  // The other vehicle is untouched.
  EXPECT_EQ(hub.subscribe(c.get(), id_of(adv, "/skiff/pose"), nullptr),
            FoxgloveHub::SubscribeOutcome::ok);
  hub.advertise("boat", app::foxglove::live_channels("boat"));
  EXPECT_EQ(id_of(json::parse(c->texts.back()), "/boat/pose"), pose);
  // A client that left receives nothing more.
  hub.leave(c.get());
  const auto texts = c->texts.size();
  hub.status(app::foxglove::LogLevel::info, "x");
  EXPECT_EQ(c->texts.size(), texts);
}

TEST(SendQueue, TelemetryReplacesItsUnsentValueInPlaceAndEventsAreBounded) {
  SendQueue<int> q(2);
  EXPECT_TRUE(q.push(1, 7u));  // telemetry of key 7
  EXPECT_TRUE(q.push(10, std::nullopt));
  EXPECT_TRUE(q.push(2, 7u));  // replaces 1, keeps its place
  EXPECT_TRUE(q.push(11, std::nullopt));
  EXPECT_FALSE(q.push(12, std::nullopt));  // a third unsent event: too slow
  SendQueue<int> r(2);
  EXPECT_TRUE(r.push(1, 7u));
  EXPECT_TRUE(r.push(10, std::nullopt));
  EXPECT_TRUE(r.push(2, 7u));
  EXPECT_TRUE(r.push(3, 8u));
  EXPECT_EQ(r.pop(), 2);
  EXPECT_EQ(r.pop(), 10);
  EXPECT_TRUE(r.push(11, std::nullopt));
  EXPECT_TRUE(r.push(12, std::nullopt));  // one event was sent: room for two again
  EXPECT_EQ(r.pop(), 3);
  EXPECT_EQ(r.pop(), 11);
  EXPECT_EQ(r.pop(), 12);
  EXPECT_TRUE(r.empty());
}

}  // namespace
