#include <gtest/gtest.h>

#include "kinematics/parse_error.hpp"
#include "sim/sim_config.hpp"

using namespace avk::sim;

namespace {
std::string error_field(const std::string& text) {
  try {
    parse_sim_config(text, "usim");
  } catch (const avk::kinematics::ParseError& e) {
    return e.field();
  }
  return "<no error>";
}
}  // namespace

TEST(SimConfig, OverridesTheKindDefaults) {
  const SimSetup s = parse_sim_config(R"({
    "vehicle": "catamaran:otter",
    "ticks_hz": {"plant": 20, "controller": 10, "helm": 5},
    "pid": {"preset": "m200_in_water", "yaw": {"kp": 0.7}},
    "current": {"speed_mps": 0.2, "toward_deg": 90},
    "wind": {"mean_speed_mps": 5, "from_deg": 270, "gust_sigma_mps": 1.5},
    "sensors": {"gnss_sigma_m": 0.5, "latency_s": 0.1, "heading_from_course_above_mps": 0.8},
    "seed": 9, "jitter_fraction": 0.1, "random_phases": true
  })",
                                      "usim");
  EXPECT_EQ(s.vehicle.kind, avk::vehicle::VehicleKind::catamaran_otter);
  ASSERT_TRUE(s.vehicle.catamaran.has_value());
  EXPECT_EQ(s.vehicle.plant_hz, 20.0);
  EXPECT_EQ(s.vehicle.controller_hz, 10.0);
  EXPECT_EQ(s.helm_hz, 5.0);
  EXPECT_EQ(s.vehicle.pid.yaw.kp, 0.7);
  EXPECT_EQ(s.vehicle.pid.yaw.ki, avk::vehicle::MarinePidConfig::m200_in_water().yaw.ki);
  EXPECT_EQ(s.vehicle.environment.current.speed_mps, 0.2);
  EXPECT_EQ(s.vehicle.environment.wind.from_deg, 270.0);
  EXPECT_EQ(s.vehicle.sensors.gnss_sigma_m, 0.5);
  EXPECT_EQ(s.vehicle.sensors.compass_sigma_deg, 1.0);  // catamaran default kept
  EXPECT_EQ(s.vehicle.sensors.heading_from_course_above_mps, 0.8);
  EXPECT_EQ(s.scheduler.seed, 9u);
  EXPECT_TRUE(s.scheduler.random_phases);
}

TEST(SimConfig, EmptyDocumentGivesTheDefaults) {
  const SimSetup s = parse_sim_config("{}", "usim");
  EXPECT_EQ(s.vehicle.kind, avk::vehicle::VehicleKind::usim);
  EXPECT_EQ(s.vehicle.usim.turn_rate, 30.0);
  EXPECT_EQ(s.vehicle_max_speed_mps(), 5.0);
}

// The thesis ran pHelmIvP at 10 Hz on the M200 (§3.4.2); the simulated kinds keep 4 Hz (Table
// 5.1). A config file still overrides either.
TEST(SimConfig, TheM200HelmRunsAt10Hz) {
  EXPECT_EQ(default_sim_setup("catamaran:m200").helm_hz, 10.0);
  EXPECT_EQ(default_sim_setup("catamaran").helm_hz, 10.0);
  EXPECT_EQ(parse_sim_config("{}", "catamaran:m200").helm_hz, 10.0);
  EXPECT_EQ(parse_sim_config(R"({"ticks_hz": {"helm": 4}})", "catamaran:m200").helm_hz, 4.0);
  EXPECT_EQ(default_sim_setup("catamaran:heron").helm_hz, 4.0);
  EXPECT_EQ(default_sim_setup("catamaran:otter").helm_hz, 4.0);
  EXPECT_EQ(default_sim_setup("usim").helm_hz, 4.0);
}

TEST(SimConfig, ErrorsNameTheField) {
  EXPECT_EQ(error_field(R"({"curent": {}})"), "/curent");
  EXPECT_EQ(error_field(R"({"current": {"speed_mps": -1}})"), "/current/speed_mps");
  EXPECT_EQ(error_field(R"({"wind": {"from_deg": "west"}})"), "/wind/from_deg");
  EXPECT_EQ(error_field(R"({"vehicle": "zeppelin"})"), "/vehicle");
  EXPECT_EQ(error_field(R"({"pid": {"preset": "fast"}})"), "/pid/preset");
  EXPECT_EQ(error_field(R"({"pid": {"yaw": {"kq": 1}}})"), "/pid/yaw/kq");
  EXPECT_EQ(error_field(R"({"ticks_hz": {"plant": 0}})"), "/ticks_hz/plant");
  EXPECT_EQ(error_field(R"({"seed": 1.5})"), "/seed");
  EXPECT_EQ(error_field(R"([1, 2])"), "/");
  EXPECT_EQ(error_field(R"({"seed": )"), "json");
}
