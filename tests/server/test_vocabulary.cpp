#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mission/event_kind.hpp"
#include "mission/helm_mode.hpp"
#include "server/serialize/vocabulary.hpp"
#include "server/stream_hub.hpp"
#include "vehicle/vehicle.hpp"

using nlohmann::json;
namespace mission = avk::mission;
namespace vehicle = avk::vehicle;

namespace {
// How often each name occurs in a JSON array of names.
std::map<std::string, int> counts(const json& names) {
  std::map<std::string, int> out;
  for (const auto& n : names)
    ++out[n.get<std::string>()];
  return out;
}
}  // namespace

TEST(Vocabulary, ListsEveryEventKindOnceWithItsSeverity) {
  const json v = avk::server::vocabulary_json();
  ASSERT_TRUE(v["event_kinds"].is_array());
  std::map<std::string, int> seen;
  for (const auto& e : v["event_kinds"]) {
    const std::string kind = e.at("kind").get<std::string>();
    ++seen[kind];
    const auto k = mission::event_kind_from_string(kind);
    ASSERT_TRUE(k) << kind;
    EXPECT_EQ(e.at("severity"), std::string(mission::to_string(mission::severity(*k)))) << kind;
  }
  EXPECT_EQ(seen.size(), mission::all_event_kinds().size());
  for (const mission::EventKind k : mission::all_event_kinds())
    EXPECT_EQ(seen[std::string(mission::to_string(k))], 1) << mission::to_string(k);
}

TEST(Vocabulary, ListsEveryHelmModeAndLinkStateOnce) {
  const json v = avk::server::vocabulary_json();
  auto modes = counts(v.at("helm_modes"));
  EXPECT_EQ(modes.size(), mission::all_helm_modes().size());
  for (const mission::HelmMode m : mission::all_helm_modes())
    EXPECT_EQ(modes[mission::to_string(m)], 1) << mission::to_string(m);
  auto links = counts(v.at("link_states"));
  EXPECT_EQ(links.size(), vehicle::all_link_states().size());
  for (const vehicle::LinkState l : vehicle::all_link_states())
    EXPECT_EQ(links[vehicle::to_string(l)], 1) << vehicle::to_string(l);
}

TEST(Vocabulary, HelloCarriesIt) {
  avk::server::StreamHub hub;
  const json hello = json::parse(hub.hello("test-1"));
  EXPECT_EQ(hello.at("type"), "hello");
  EXPECT_EQ(hello.at("server_version"), "test-1");
  EXPECT_EQ(hello.at("session_id"), hub.session_id());
  const json v = avk::server::vocabulary_json();
  for (const char* key : {"event_kinds", "helm_modes", "link_states"})
    EXPECT_EQ(hello.at(key), v.at(key)) << key;
}

TEST(Vocabulary, StatusOfAKindGoesOutAtItsSeverity) {
  struct Collect final : avk::server::StreamSink {
    std::vector<json> got;
    void deliver(std::shared_ptr<const avk::server::StreamMessage> m) override {
      got.push_back(json::parse(*m->payload));
    }
  };
  avk::server::StreamHub hub;
  const auto sink = std::make_shared<Collect>();
  hub.subscribe(sink, "status");
  hub.status(1.0, mission::EventKind::link, "navigation lost");
  hub.status(2.0, mission::EventKind::mission_attached, "mission 1 started");
  ASSERT_EQ(sink->got.size(), 2u);
  EXPECT_EQ(sink->got[0]["data"]["kind"], "link");
  EXPECT_EQ(sink->got[0]["data"]["level"], "warning");
  EXPECT_EQ(sink->got[1]["data"]["kind"], "mission_attached");
  EXPECT_EQ(sink->got[1]["data"]["level"], "info");
}
