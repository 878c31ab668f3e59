// Turn-array entries with a commanded speed change (u0 -> u1).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <nlohmann/json.hpp>

#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"
#include "support/example_file.hpp"
#include "support/mission_field_errors.hpp"

using namespace avk::mission;
using nlohmann::json;

namespace {

json fig41() {
  return json::parse(avk::testing::example_text("thesis-fig4-1.json"));
}

std::vector<std::string> fields_of(const json& doc, double vmax = 2.0) {
  return avk::testing::mission_field_errors([&](json& d) { d = doc; }, vmax);
}

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

TEST(SpeedChanges, AreReadAndPlannedForEveryHeadingChangeAfterTheConstantSpeedTurns) {
  json doc = fig41();
  doc["turn_array"]["speeds_mps"] = {1.0};
  doc["turn_array"]["dheadings_deg"] = {45, 90};
  doc["turn_array"]["repeats"] = 2;
  doc["turn_array"]["speed_changes"] = {{{"from_mps", 1.5}, {"to_mps", 0.75}},
                                        {{"from_mps", 1.0}, {"to_mps", 0.5}}};
  const MissionConfig c = parse_mission_config(doc.dump(), 1.7);
  ASSERT_EQ(c.turn_array.speed_changes.size(), 2u);
  EXPECT_EQ(c.turn_array.speed_changes[0], (SpeedChange{1.5, 0.75}));
  const auto plan = plan_turns(c);
  ASSERT_EQ(plan.size(), 3u * 2u * 2u);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_FALSE(plan[i].speed_after_mps) << i;
  EXPECT_EQ(plan[4].speed_mps, 1.5);
  EXPECT_EQ(plan[4].speed_after_mps, 0.75);
  EXPECT_EQ(plan[11].speed_mps, 1.0);
  EXPECT_EQ(plan[11].speed_after_mps, 0.5);
  EXPECT_EQ(plan[11].dheading_deg, 90.0);
}

TEST(SpeedChanges, MakeSpeedsOptionalButNotBothAbsent) {
  json doc = fig41();
  doc["turn_array"].erase("speeds_mps");
  EXPECT_TRUE(has(fields_of(doc), "/turn_array/speeds_mps"));
  doc["turn_array"]["speed_changes"] = {{{"from_mps", 1.5}, {"to_mps", 0.75}}};
  EXPECT_TRUE(fields_of(doc).empty());
  const MissionConfig c = parse_mission_config(doc.dump(), 1.7);
  EXPECT_EQ(return_speed_mps(c), 1.5);
}

TEST(SpeedChanges, BadEntriesAreNamedByPointer) {
  json doc = fig41();
  doc["turn_array"]["speed_changes"] = {
      {{"from_mps", 1.5}, {"to_mps", 0.75}},  // fine
      {{"from_mps", 1.0}, {"to_mps", 1.0}},   // no change
      {{"from_mps", 3.0}, {"to_mps", 1.0}},   // above the vehicle's maximum
      {{"from_mps", 1.0}},                    // to_mps missing
      {{"from_mps", 1.5}, {"to_mps", 0.74}},  // duplicates entry 0
      {{"from_mps", 1.0}, {"to_mps", 0.5}, {"ratio", 2}},
      7};
  const auto f = fields_of(doc);
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/1/to_mps"));
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/2/from_mps"));
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/3/to_mps"));
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/4"));
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/5/ratio"));
  EXPECT_TRUE(has(f, "/turn_array/speed_changes/6"));
  EXPECT_FALSE(has(f, "/turn_array/speed_changes/0"));
  EXPECT_FALSE(has(f, "/turn_array/speed_changes/0/to_mps"));

  doc["turn_array"]["speed_changes"] = json::array();
  EXPECT_TRUE(has(fields_of(doc), "/turn_array/speed_changes"));
  json many = json::array();
  for (std::size_t i = 0; i <= kMaxMissionSpeedChanges; ++i)
    many.push_back({{"from_mps", 1.5}, {"to_mps", 0.01 + 0.06 * static_cast<double>(i)}});
  doc["turn_array"]["speed_changes"] = many;
  EXPECT_TRUE(has(fields_of(doc), "/turn_array/speed_changes"));
}

TEST(SpeedChanges, CountTowardsThePlannedTurns) {
  json doc = fig41();
  doc["turn_array"]["speeds_mps"] = {1.0};
  doc["turn_array"]["dheadings_deg"] = json::array();
  for (int d = 5; d <= 180; d += 5)
    doc["turn_array"]["dheadings_deg"].push_back(d);  // 36
  doc["turn_array"]["repeats"] = 28;                  // 1 x 36 x 28 = 1008: fine alone
  EXPECT_TRUE(fields_of(doc).empty());
  doc["turn_array"]["speed_changes"] = {{{"from_mps", 1.5}, {"to_mps", 0.75}}};  // 2016
  EXPECT_TRUE(has(fields_of(doc), "/turn_array"));
}

TEST(SpeedChanges, ACellWithASpeedChangeIsNotTheConstantSpeedCell) {
  EXPECT_FALSE(same_cell(1.5, 0.75, 90, 1.5, std::nullopt, 90));
  EXPECT_FALSE(same_cell(1.5, 0.75, 90, 1.5, 1.0, 90));
  EXPECT_TRUE(same_cell(1.5, 0.75, 90, 1.5, 0.76, 90.2));
  EXPECT_TRUE(same_cell(1.5, std::nullopt, 90, 1.5, std::nullopt, 90));
  // A resumed mission skips the speed-change turns done, not the constant-speed ones.
  json doc = fig41();
  doc["turn_array"]["speeds_mps"] = {1.5};
  doc["turn_array"]["dheadings_deg"] = {90};
  doc["turn_array"]["speed_changes"] = {{{"from_mps", 1.5}, {"to_mps", 0.75}}};
  const auto plan = plan_turns(parse_mission_config(doc.dump(), 1.7));
  const auto left = remaining_turns(plan, {{1.5, 90, 1, 0.75}});
  ASSERT_EQ(left.size(), 1u);
  EXPECT_FALSE(left[0].speed_after_mps);
}

// The cells a mission may plan (speeds 0.05 m/s apart, heading changes 0.5 deg apart) are told
// apart, whichever way the decimals round in binary; a resumed mission skips only its own cell.
TEST(SpeedChanges, CellsTheDocumentedSpacingApartAreTwoCells) {
  EXPECT_FALSE(same_cell(1.1, 90, 1.15, 90));
  EXPECT_FALSE(same_cell(1.0, 90, 1.05, 90));
  EXPECT_FALSE(same_cell(1.1, 40.1, 1.1, 40.6));
  EXPECT_FALSE(same_cell(1.5, 1.1, 90, 1.5, 1.15, 90));
  EXPECT_TRUE(same_cell(1.1, 90, 1.1499, 90.4));
  json doc = fig41();
  doc["turn_array"]["speeds_mps"] = {1.1, 1.15};
  doc["turn_array"]["dheadings_deg"] = {90};
  doc["turn_array"]["repeats"] = 1;
  const auto plan = plan_turns(parse_mission_config(doc.dump(), 1.7));
  ASSERT_EQ(plan.size(), 2u);
  const auto left = remaining_turns(plan, {{1.1, 90, 1, std::nullopt}});
  ASSERT_EQ(left.size(), 1u);
  EXPECT_DOUBLE_EQ(left[0].speed_mps, 1.15);
}

TEST(SpeedChanges, TheExampleMissionFliesBothChangesAtThreeHeadingChanges) {
  const MissionConfig c =
      parse_mission_config(avk::testing::example_text("speed-change.json"), 1.8);
  EXPECT_EQ(c.turn_array.speed_changes, (std::vector<SpeedChange>{{1.5, 0.75}, {1.0, 0.5}}));
  EXPECT_EQ(plan_turns(c).size(), (2u + 2u) * 3u * 3u);
}
