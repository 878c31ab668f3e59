// The Foxglove channels' messages: headings as Foxglove's yaw quaternions (analytic cases),
// timestamps, the flat navigation message, turn and region scenes, and the live feed's decisions
// (advertise, unadvertise when the vehicle goes away, build only what is wanted, latch scenes).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "app/foxglove/channels.hpp"
#include "app/foxglove/messages.hpp"
#include "app/foxglove/schemas.hpp"
#include "app/foxglove_live.hpp"
#include "app/foxglove_scene.hpp"
#include "app/mission_plans.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"

namespace {

using namespace avk;
using namespace avk::app::foxglove;
using nlohmann::json;

// The unit vector a quaternion turns +x (Foxglove's forward) into.
std::pair<double, double> forward(const Quaternion& q) {
  return {1.0 - 2.0 * (q.y * q.y + q.z * q.z), 2.0 * (q.x * q.y + q.w * q.z)};
}

TEST(FoxgloveMessages, AHeadingPointsTheVehiclesForwardAxisAlongIt) {
  for (const double h : {0.0, 28.0, 55.0, 90.0, 117.0, 180.0, 243.0, 270.0, 359.0}) {
    const auto [east, north] = forward(heading_quaternion(h));
    const double rad = h * std::numbers::pi / 180.0;
    EXPECT_NEAR(east, std::sin(rad), 1e-12) << h;
    EXPECT_NEAR(north, std::cos(rad), 1e-12) << h;
    const auto q = heading_quaternion(h);
    EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0, 1e-12);
  }
}

TEST(FoxgloveMessages, TimestampsAreTheStationClockInNanoseconds) {
  EXPECT_EQ(to_ns(0.0), 0u);
  EXPECT_EQ(to_ns(-3.0), 0u);
  EXPECT_EQ(to_ns(716.25), 716'250'000'000u);
  EXPECT_DOUBLE_EQ(to_s(to_ns(12.5)), 12.5);
  NavigationState s;
  s.t_s = 894.5;
  const auto pose = json::parse(pose_message(s));
  EXPECT_EQ(pose["timestamp"]["sec"], 894);
  EXPECT_EQ(pose["timestamp"]["nsec"], 500'000'000);
  EXPECT_EQ(pose["frame_id"], kGridFrame);
}

TEST(FoxgloveMessages, NavigationIsFlatWithNullsForWhatTheVehicleDoesNotReport) {
  NavigationState s;
  s.t_s = 10.0;
  s.x_m = 3.0;
  s.y_m = -4.0;
  s.heading_deg = 45.0;
  s.speed_mps = 1.2;
  s.desired_heading_deg = 90.0;
  s.helm_mode = "turning";
  const auto j = json::parse(navigation_message(s));
  EXPECT_EQ(j["x_m"], 3.0);
  EXPECT_EQ(j["desired_heading_deg"], 90.0);
  EXPECT_TRUE(j["desired_speed_mps"].is_null());
  EXPECT_TRUE(j["yaw_rate_dps"].is_null());
  EXPECT_EQ(j["helm_mode"], "turning");
  // Every member the schema requires is present.
  const auto schema = json::parse(channel_spec("v", ChannelKind::navigation).schema);
  for (const auto& k : schema["required"])
    EXPECT_TRUE(j.contains(k.get<std::string>())) << k;
}

TEST(FoxgloveMessages, TheTransformPlacesTheVehiclesFrameInTheGrid) {
  NavigationState s;
  s.x_m = 5.0;
  s.y_m = 6.0;
  s.heading_deg = 90.0;
  const auto j = json::parse(transform_message(s, "boat"));
  EXPECT_EQ(j["parent_frame_id"], kGridFrame);
  EXPECT_EQ(j["child_frame_id"], vehicle_frame("boat"));
  EXPECT_EQ(j["translation"]["x"], 5.0);
  // Heading east is Foxglove's yaw 0: the identity rotation.
  EXPECT_NEAR(j["rotation"]["w"].get<double>(), 1.0, 1e-12);
}

TEST(FoxgloveMessages, ChannelsUseFoxglovesWellKnownSchemasVerbatim) {
  for (const auto& c : live_channels("boat")) {
    EXPECT_EQ(c.topic.rfind("/boat/", 0), 0u) << c.topic;
    const auto schema = json::parse(c.schema);
    EXPECT_EQ(schema["title"], c.schema_name);
    if (c.schema_name.rfind("foxglove.", 0) == 0) {
      EXPECT_EQ(std::string(c.schema), std::string(*well_known_schema(c.schema_name)));
    }
    EXPECT_EQ(channel_kind_of(c.topic, "boat"), c.kind);
  }
  EXPECT_FALSE(channel_kind_of("/other/pose", "boat"));
  EXPECT_FALSE(well_known_schema("foxglove.Unknown"));
  // Telemetry is latest-value-wins, events are not; scenes are latched.
  EXPECT_TRUE(channel_spec("b", ChannelKind::pose).latest_value_wins);
  EXPECT_FALSE(channel_spec("b", ChannelKind::log).latest_value_wins);
  EXPECT_TRUE(channel_spec("b", ChannelKind::region).latched);
  EXPECT_TRUE(channel_spec("b", ChannelKind::turn).latched);
}

TEST(FoxgloveMessages, TheRegionSceneHasTheBoundaryLoopAndTheBufferInsideIt) {
  mission::OperatingRegion r;
  r.polygon = {{-50, -50}, {50, -50}, {50, 50}, {-50, 50}};
  r.buffer_m = 10.0;
  const auto j = json::parse(region_scene_message(3.0, r));
  const auto& lines = j["entities"][0]["lines"];
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0]["type"], 1);  // LINE_LOOP
  for (const auto& p : lines[1]["points"]) {
    EXPECT_NEAR(std::abs(p["x"].get<double>()), 40.0, 1e-9);
    EXPECT_NEAR(std::abs(p["y"].get<double>()), 40.0, 1e-9);
  }
}

TEST(FoxgloveMessages, ATurnSceneDrawsEveryPredictionTheCorridorAndReplacesThePreviousTurn) {
  TurnScene s;
  s.t_s = 50.0;
  s.start = {10.0, 20.0, 0.0};
  s.goal_heading_deg = 90.0;
  s.dheading_deg = 90.0;
  s.state = "running";
  kinematics::CorridorBand band;
  band.left = {{9, 20}, {9, 25}};
  band.right = {{11, 20}, {11, 25}};
  s.predictions = {
      {"avk", {{10, 20}, {10, 25}}, band, "ground", "0.20 m/s toward 180 deg (live)"},
      {"instantaneous", {{10, 20}, {30, 20}}, {}, "ground", "0.20 m/s toward 180 deg (live)"}};
  s.cell_label = "CKT 1.00 m/s +90 deg (cell)";
  const auto j = json::parse(turn_scene_message(s));
  EXPECT_EQ(j["deletions"][0]["type"], 1);  // ALL: nothing of the last turn lingers
  std::map<std::string, json> by_id;
  for (const auto& e : j["entities"])
    by_id[e["id"].get<std::string>()] = e;
  ASSERT_TRUE(by_id.contains("turn/avk"));
  EXPECT_EQ(by_id["turn/avk"]["lines"].size(), 3u);  // the trajectory and the two corridor edges
  EXPECT_EQ(by_id["turn/instantaneous"]["lines"].size(), 1u);
  // The goal ray leaves the start toward the goal heading (east).
  const auto& ray = by_id["turn/goal"]["lines"][0]["points"];
  EXPECT_NEAR(ray[1]["x"].get<double>() - 10.0, 30.0, 1e-9);
  EXPECT_NEAR(ray[1]["y"].get<double>(), 20.0, 1e-9);
  EXPECT_NE(by_id["turn/cell"]["texts"][0]["text"].get<std::string>().find("+90"),
            std::string::npos);
  // What the predictions move against is said on each and on the cell's label.
  const auto meta_of = [&](const std::string& id) {
    std::map<std::string, std::string> meta;
    for (const auto& kv : by_id[id]["metadata"])
      meta[kv["key"].get<std::string>()] = kv["value"].get<std::string>();
    return meta;
  };
  EXPECT_EQ(meta_of("turn/avk").at("frame"), "ground");
  EXPECT_EQ(meta_of("turn/avk").at("current"), "0.20 m/s toward 180 deg (live)");
  EXPECT_EQ(meta_of("turn/cell").at("frame"), "ground");
  EXPECT_NE(by_id["turn/cell"]["texts"][0]["text"].get<std::string>().find("predicted over ground"),
            std::string::npos);
}

// A sink that records what the feed sends, with a chosen set of wanted topics.
struct RecordingSink final : FoxgloveSink {
  std::vector<std::string> advertised, unadvertised;
  std::multimap<std::string, std::string> published;
  std::vector<std::string> statuses;
  std::set<std::string> wanted_topics;
  std::size_t times = 0;
  void advertise(const std::string& v, const std::vector<ChannelSpec>&) override {
    advertised.push_back(v);
  }
  void unadvertise(const std::string& v) override { unadvertised.push_back(v); }
  bool wanted(const std::string& t) const override { return wanted_topics.contains(t); }
  void publish(const std::string& t, std::uint64_t, std::string p) override {
    published.emplace(t, std::move(p));
  }
  void status(LogLevel, const std::string& m) override { statuses.push_back(m); }
  void time(std::uint64_t) override { ++times; }
};

app::VehicleSnapshot snapshot(const std::string& vid, vehicle::LinkState link, double t_s) {
  app::VehicleSnapshot s;
  s.info.id = vid;
  s.link = link;
  s.t_s = t_s;
  vehicle::NavSample n;
  n.t_s = t_s;
  n.x_m = t_s;
  s.nav = n;
  return s;
}

TEST(FoxgloveLiveFeed, AdvertisesOnTheFirstReportAndWithdrawsWhenTheLinkIsLost) {
  RecordingSink sink;
  FoxgloveLive live(sink, nullptr);
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 1.0));
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 1.1));
  ASSERT_EQ(sink.advertised, std::vector<std::string>{"boat"});
  live.telemetry(snapshot("boat", vehicle::LinkState::disconnected, 1.2));
  EXPECT_EQ(sink.unadvertised, std::vector<std::string>{"boat"});
  // Back again: the same channels are offered again.
  live.telemetry(snapshot("boat", vehicle::LinkState::stale, 1.3));
  EXPECT_EQ(sink.advertised.size(), 2u);
  live.withdraw();
  EXPECT_EQ(sink.unadvertised.size(), 2u);
}

TEST(FoxgloveLiveFeed, BuildsOnlyWhatAClientWants) {
  RecordingSink sink;
  FoxgloveLive live(sink, nullptr);
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 1.0));
  EXPECT_TRUE(sink.published.empty());
  EXPECT_EQ(sink.times, 1u);
  sink.wanted_topics = {topic("boat", ChannelKind::pose)};
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 2.0));
  ASSERT_EQ(sink.published.size(), 1u);
  EXPECT_EQ(sink.published.begin()->first, "/boat/pose");
  // No latitude/longitude in the navigation: no location, even when wanted.
  sink.wanted_topics.insert(topic("boat", ChannelKind::location));
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 3.0));
  EXPECT_EQ(sink.published.count("/boat/location"), 0u);
}

TEST(FoxgloveLiveFeed, AVehicleReportingLatitudeAndLongitudeHasItsLocationFix) {
  RecordingSink sink;
  FoxgloveLive live(sink, nullptr);
  sink.wanted_topics = {topic("boat", ChannelKind::location)};
  auto s = snapshot("boat", vehicle::LinkState::live, 4.0);
  s.nav->lat_deg = 42.358456;
  s.nav->lon_deg = -71.087589;
  live.telemetry(s);
  const auto range = sink.published.equal_range("/boat/location");
  ASSERT_EQ(std::distance(range.first, range.second), 1);
  const auto fix = json::parse(range.first->second);
  EXPECT_DOUBLE_EQ(fix["latitude"].get<double>(), 42.358456);
  EXPECT_DOUBLE_EQ(fix["longitude"].get<double>(), -71.087589);
  EXPECT_EQ(fix["position_covariance"].size(), 9u);
  EXPECT_EQ(fix["frame_id"], vehicle_frame("boat"));
}

TEST(FoxgloveLiveFeed, WithADatumASimulatedVehicleIsPlacedOnTheEarth) {
  RecordingSink sink;
  FoxgloveLive live(sink, nullptr, vehicle::LatLon{42.358456, -71.087589});
  sink.wanted_topics = {topic("boat", ChannelKind::location)};
  auto s = snapshot("boat", vehicle::LinkState::live, 0.0);  // at the grid's origin
  live.telemetry(s);
  s = snapshot("boat", vehicle::LinkState::live, 100.0);  // 100 m east
  live.telemetry(s);
  std::vector<json> fixes;
  for (auto [it, end] = sink.published.equal_range("/boat/location"); it != end; ++it)
    fixes.push_back(json::parse(it->second));
  ASSERT_EQ(fixes.size(), 2u);
  EXPECT_NEAR(fixes[0]["latitude"].get<double>(), 42.358456, 1e-9);
  EXPECT_NEAR(fixes[0]["longitude"].get<double>(), -71.087589, 1e-9);
  // 100 m east at 42.36 deg N: 100 / (cos(lat) * 111.32 km) of longitude.
  const double dlon = fixes[1]["longitude"].get<double>() + 71.087589;
  EXPECT_NEAR(dlon, 100.0 / (std::cos(42.358456 * std::numbers::pi / 180.0) * 111'320.0), 2e-6);
  EXPECT_NEAR(fixes[1]["latitude"].get<double>(), 42.358456, 1e-6);
}

TEST(FoxgloveLiveFeed, StationEventsBecomeStatusAndLogs) {
  RecordingSink sink;
  FoxgloveLive live(sink, nullptr);
  live.telemetry(snapshot("boat", vehicle::LinkState::live, 1.0));
  sink.wanted_topics = {topic("boat", ChannelKind::log)};
  live.station_event(2.0, mission::EventKind::mission_attached, "mission 3 attached");
  ASSERT_EQ(sink.statuses.size(), 1u);
  const auto range = sink.published.equal_range("/boat/log");
  ASSERT_EQ(std::distance(range.first, range.second), 1);
  const auto log = json::parse(range.first->second);
  EXPECT_EQ(log["message"], "mission 3 attached");
  EXPECT_EQ(log["name"], "boat/mission_attached");
}

}  // namespace

namespace {

// What the runner told its observers when each turn began.
struct StartsSeen final : mission::MissionObserver {
  void on_turn_started(const mission::TurnTask&, const mission::RunningTurn& t) override {
    turns.push_back(t);
  }
  std::vector<mission::RunningTurn> turns;
};

}  // namespace

// A half turn's goal is as far one way as the other: the scene must take the side the runner
// chose (port here), not guess it from headings, and start where the runner started the turn.
TEST(FoxgloveLiveFeed, AHalfTurnToPortIsDrawnToPortFromWhereItStarted) {
  constexpr const char* kHalfTurn = R"({
    "name": "half turn",
    "turn_array": {"speeds_mps": [1.0], "dheadings_deg": [180], "direction": "left"},
    "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                         "buffer_m": 25, "return_point_m": [0, -70]}})";
  const auto config = mission::parse_mission_config(kHalfTurn, 2.0);
  sim::SimMissionOptions so;
  so.setup = sim::default_sim_setup("usim");
  so.start = app::start_pose(config);
  sim::SimMission sim(so);
  mission::RunnerOptions ro;
  ro.vehicle_id = "usim";
  mission::MissionRunner runner(config, sim.vehicle(), mission::plan_turns(config), ro);

  RecordingSink sink;
  FoxgloveLive live(sink, nullptr);
  live.telemetry(snapshot("usim", vehicle::LinkState::live, 0.0));  // advertises the channels
  sink.wanted_topics = {topic("usim", ChannelKind::turn)};
  auto follower = live.follow(7, runner);
  StartsSeen seen;
  runner.add_observer(*follower);
  runner.add_observer(seen);
  sim::FastPacer pacer;
  sim.run(runner, pacer);
  live.withdraw();

  ASSERT_EQ(seen.turns.size(), 1u);
  const mission::RunningTurn& told = seen.turns.front();
  EXPECT_DOUBLE_EQ(told.dheading_deg, -180.0);
  // The first turn scene is the one drawn at the start.
  const auto range = sink.published.equal_range("/usim/turn");
  ASSERT_NE(range.first, range.second);
  const auto scene = json::parse(range.first->second);
  std::map<std::string, json> by_id;
  for (const auto& e : scene["entities"])
    by_id[e["id"].get<std::string>()] = e;
  ASSERT_TRUE(by_id.contains("turn/cell"));
  std::map<std::string, std::string> meta;
  for (const auto& kv : by_id["turn/cell"]["metadata"])
    meta[kv["key"].get<std::string>()] = kv["value"].get<std::string>();
  EXPECT_DOUBLE_EQ(std::stod(meta.at("dheading_deg")), -180.0);
  const auto& at = by_id["turn/cell"]["texts"][0]["pose"]["position"];
  EXPECT_DOUBLE_EQ(at["x"].get<double>(), told.start.x_m);
  EXPECT_DOUBLE_EQ(at["y"].get<double>(), told.start.y_m);
  // The goal ray points along the goal heading, the start heading reversed.
  const auto& ray = by_id["turn/goal"]["lines"][0]["points"];
  const double gx = ray[1]["x"].get<double>() - ray[0]["x"].get<double>();
  const double gy = ray[1]["y"].get<double>() - ray[0]["y"].get<double>();
  const double start_rad = told.start.heading_deg * std::numbers::pi / 180.0;
  EXPECT_NEAR(gx / std::hypot(gx, gy), -std::sin(start_rad), 1e-9);
  EXPECT_NEAR(gy / std::hypot(gx, gy), -std::cos(start_rad), 1e-9);
}
