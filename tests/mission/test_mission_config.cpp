#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>

#include "mission/mission_config.hpp"
#include "support/example_file.hpp"
#include "support/mission_field_errors.hpp"

using namespace avk::mission;
using nlohmann::json;

namespace {

using avk::testing::example_text;

// Fields named by the validation of a mutated copy of the Figure 4-1 mission.
std::vector<std::string> fields_of(const std::function<void(json&)>& mutate, double vmax = 2.0) {
  return avk::testing::mission_field_errors(mutate, vmax);
}

}  // namespace

TEST(MissionConfig, ThesisFigure41Example) {
  const MissionConfig c = parse_mission_config(example_text("thesis-fig4-1.json"), 1.7);
  EXPECT_EQ(c.name, "thesis-fig4-1");
  EXPECT_EQ(c.turn_array.speeds_mps, (std::vector<double>{0.5, 1.0, 1.5}));
  EXPECT_EQ(c.turn_array.dheadings_deg.size(), 6u);
  EXPECT_EQ(c.turn_array.direction, DirectionPolicy::alternate);
  EXPECT_EQ(c.condition_set.window, 5);
  EXPECT_EQ(c.completion.threshold_deg, 5.0);
  EXPECT_EQ(c.completion.fraction, 0.1);  // defaults: the example does not set them
  EXPECT_EQ(c.completion.floor_deg, 1.0);
  EXPECT_EQ(c.region.polygon.size(), 4u);
  EXPECT_EQ(c.region.buffer_m, 25.0);
}

TEST(MissionConfig, OffGridExampleFliesBetweenTheFigure41Cells) {
  const MissionConfig c = parse_mission_config(example_text("off-grid-turns.json"), 1.7);
  EXPECT_EQ(c.turn_array.speeds_mps, (std::vector<double>{0.75, 1.25}));
  EXPECT_EQ(c.turn_array.dheadings_deg, (std::vector<double>{25, 55, 85, 115, 145}));
  EXPECT_EQ(c.condition_set.max_heading_error_deg, 2.0);
}

TEST(MissionConfig, PersistentExcitationExample) {
  const MissionConfig c = parse_mission_config(example_text("persistent-excitation.json"), 1.7);
  EXPECT_EQ(c.kind, MissionKind::persistent_excitation);
  ASSERT_TRUE(c.excitation.has_value());
  EXPECT_EQ(c.excitation->seed, 7u);
}

TEST(MissionConfig, EveryProblemIsNamed) {
  using V = std::vector<std::string>;
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["speeds_mps"] = json::array(); }),
            V{"/turn_array/speeds_mps"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["speeds_mps"][2] = 3.0; }),
            V{"/turn_array/speeds_mps/2"});  // above the vehicle's maximum
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["dheadings_deg"][0] = 0; }),
            V{"/turn_array/dheadings_deg/0"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["dheadings_deg"][1] = 190; }),
            V{"/turn_array/dheadings_deg/1"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["direction"] = "sideways"; }),
            V{"/turn_array/direction"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_aray"] = 1; }), V{"/turn_aray"});
  EXPECT_EQ(fields_of([](json& d) { d["condition_set"]["speed_tolerance_kts"] = 1; }),
            V{"/condition_set/speed_tolerance_kts"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_threshold_deg"] = "5"; }),
            V{"/constant_heading/completion_threshold_deg"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_fraction"] = 0; }),
            V{"/constant_heading/completion_fraction"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_fraction"] = 1.5; }),
            V{"/constant_heading/completion_fraction"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_fraction"] = "10%"; }),
            V{"/constant_heading/completion_fraction"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_floor_deg"] = -1; }),
            V{"/constant_heading/completion_floor_deg"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["completion_floor_deg"] = 6; }),
            V{"/constant_heading/completion_floor_deg"});  // above the 5 deg threshold
  EXPECT_EQ(fields_of([](json& d) {
              d["operating_region"]["polygon_m"] = {{0, 0}, {100, 100}, {100, 0}, {0, 100}};
            }),
            V{"/operating_region/polygon_m"});  // a bow tie
  EXPECT_EQ(fields_of([](json& d) {
              d["operating_region"]["polygon_m"] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
              d["operating_region"]["return_point_m"] = {5, 5};
            }),
            V{"/operating_region/polygon_m"});  // too small
  EXPECT_EQ(fields_of([](json& d) { d["operating_region"]["buffer_m"] = 120; }),
            V{"/operating_region/buffer_m"});
  EXPECT_EQ(fields_of([](json& d) {
              d["operating_region"]["return_point_m"] = {500, 0};
            }),
            V{"/operating_region/return_point_m"});
  EXPECT_EQ(fields_of([](json& d) { d.erase("name"); }), V{"/name"});
  // Several problems at once are all reported.
  EXPECT_EQ(fields_of([](json& d) {
              d["turn_array"]["repeats"] = 0;
              d["operating_region"].erase("return_point_m");
            }).size(),
            2u);
}

TEST(MissionConfig, BadJsonIsAnError) {
  try {
    parse_mission_config("{\"name\": ", 1.0);
    FAIL();
  } catch (const MissionConfigError& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].field, "json");
  }
}

TEST(Polygon, AreaSimplicityAndContainment) {
  const avk::kinematics::Polyline square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_DOUBLE_EQ(polygon_area_m2(square), 100.0);
  EXPECT_TRUE(polygon_is_simple(square));
  EXPECT_FALSE(polygon_is_simple({{0, 0}, {10, 10}, {10, 0}, {0, 10}}));
  EXPECT_TRUE(point_in_polygon({5, 5}, square));
  EXPECT_FALSE(point_in_polygon({15, 5}, square));
  EXPECT_DOUBLE_EQ(distance_to_boundary_m({5, 2}, square), 2.0);
  EXPECT_DOUBLE_EQ(distance_to_boundary_m({5, 9}, square), 1.0);
}

TEST(MissionConfig, RunnerFieldsHaveDefaultsAndRanges) {
  const MissionConfig c = parse_mission_config(example_text("thesis-fig4-1.json"), 1.7);
  EXPECT_EQ(c.turn_array.max_attempts, 10);
  EXPECT_DOUBLE_EQ(c.turn_timeout_s, 120.0);
  EXPECT_FALSE(c.region.return_speed_mps.has_value());
  EXPECT_DOUBLE_EQ(return_speed_mps(c), 0.5);  // the first speed of the turn array
  EXPECT_DOUBLE_EQ(c.region.capture_radius_m, 3.0);

  json doc = json::parse(example_text("thesis-fig4-1.json"));
  doc["turn_array"]["max_attempts"] = 3;
  doc["constant_heading"]["timeout_s"] = 60;
  doc["operating_region"]["return_speed_mps"] = 1.2;
  doc["operating_region"]["capture_radius_m"] = 5;
  const MissionConfig set = parse_mission_config(doc.dump(), 1.7);
  EXPECT_EQ(set.turn_array.max_attempts, 3);
  EXPECT_DOUBLE_EQ(set.turn_timeout_s, 60.0);
  EXPECT_DOUBLE_EQ(return_speed_mps(set), 1.2);
  EXPECT_DOUBLE_EQ(set.region.capture_radius_m, 5.0);

  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["max_attempts"] = 0; }),
            std::vector<std::string>{"/turn_array/max_attempts"});
  EXPECT_EQ(fields_of([](json& d) { d["constant_heading"]["timeout_s"] = -1; }),
            std::vector<std::string>{"/constant_heading/timeout_s"});
  // A return speed above the vehicle's maximum is as impossible as a turn speed above it.
  EXPECT_EQ(fields_of([](json& d) { d["operating_region"]["return_speed_mps"] = 3.0; }, 2.0),
            std::vector<std::string>{"/operating_region/return_speed_mps"});
  EXPECT_EQ(fields_of([](json& d) { d["operating_region"]["capture_radius_m"] = "3"; }),
            std::vector<std::string>{"/operating_region/capture_radius_m"});
}

TEST(MissionConfig, CompletionRuleFieldsAreReadAndChecked) {
  json doc = json::parse(example_text("thesis-fig4-1.json"));
  doc["constant_heading"]["completion_fraction"] = 0.2;
  doc["constant_heading"]["completion_floor_deg"] = 0.5;
  const MissionConfig set = parse_mission_config(doc.dump(), 1.7);
  EXPECT_DOUBLE_EQ(set.completion.threshold_deg, 5.0);
  EXPECT_DOUBLE_EQ(set.completion.fraction, 0.2);
  EXPECT_DOUBLE_EQ(set.completion.floor_deg, 0.5);

  // A file from before the floor, with a threshold below the default floor, still loads.
  json old = json::parse(example_text("thesis-fig4-1.json"));
  old["constant_heading"] = {{"completion_threshold_deg", 0.5}};
  EXPECT_DOUBLE_EQ(parse_mission_config(old.dump(), 1.7).completion.threshold_deg, 0.5);
  // Every problem of the section at once, each by its field.
  EXPECT_EQ(fields_of([](json& d) {
              d["constant_heading"] = {{"completion_threshold_deg", 2},
                                       {"completion_fraction", -0.1},
                                       {"completion_floor_deg", 3}};
            }),
            (std::vector<std::string>{"/constant_heading/completion_fraction",
                                      "/constant_heading/completion_floor_deg"}));
}

TEST(MissionConfig, InitialYawRateAxis) {
  json doc = json::parse(example_text("thesis-fig4-1.json"));
  doc["turn_array"]["initial_yaw_rates_dps"] = {-10, 0, 10};
  doc["turn_array"]["initial_yaw_rate_band_dps"] = 2.0;
  doc["turn_array"]["pre_turn_dheading_deg"] = 60;
  const MissionConfig c = parse_mission_config(doc.dump(), 2.0);
  EXPECT_EQ(c.turn_array.initial_yaw_rates_dps, (std::vector<double>{-10, 0, 10}));
  EXPECT_DOUBLE_EQ(c.turn_array.initial_yaw_rate_band_dps, 2.0);
  EXPECT_DOUBLE_EQ(c.turn_array.pre_turn_dheading_deg, 60.0);
  EXPECT_DOUBLE_EQ(c.turn_array.initial_yaw_rate_timeout_s, 30.0);
  const MissionConfig plain = parse_mission_config(example_text("thesis-fig4-1.json"), 2.0);
  EXPECT_TRUE(plain.turn_array.initial_yaw_rates_dps.empty());
  EXPECT_DOUBLE_EQ(plain.turn_array.initial_yaw_rate_band_dps, 1.5);

  using V = std::vector<std::string>;
  EXPECT_EQ(fields_of([](json& d) {
              d["turn_array"]["initial_yaw_rates_dps"] = {5, 70};
            }),
            V{"/turn_array/initial_yaw_rates_dps/1"});
  EXPECT_EQ(fields_of([](json& d) {
              d["turn_array"]["initial_yaw_rates_dps"] = {5, 5.2};
            }),
            V{"/turn_array/initial_yaw_rates_dps/1"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["initial_yaw_rates_dps"] = "fast"; }),
            V{"/turn_array/initial_yaw_rates_dps"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["initial_yaw_rate_band_dps"] = 0; }),
            V{"/turn_array/initial_yaw_rate_band_dps"});
  EXPECT_EQ(fields_of([](json& d) { d["turn_array"]["pre_turn_dheading_deg"] = 200; }),
            V{"/turn_array/pre_turn_dheading_deg"});
  // The new axis counts towards the planned turns: 3 x 6 x 9 x 13 repeats > 2000.
  EXPECT_EQ(fields_of([](json& d) {
              d["turn_array"]["initial_yaw_rates_dps"] = {-8, -6, -4, -2, 0, 2, 4, 6, 8};
              d["turn_array"]["repeats"] = 13;
            }),
            V{"/turn_array"});
}
