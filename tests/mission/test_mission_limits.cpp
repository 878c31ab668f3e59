// Mission input limits: a mission is input from outside, so its size is bounded, its duplicates
// refused, and a number JSON cannot hold named like any other bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "mission/mission_config.hpp"

using namespace avk::mission;
using nlohmann::json;

namespace {

json base_mission() {
  return json::parse(R"({
    "name": "limits",
    "turn_array": {"speeds_mps": [0.5, 1.0], "dheadings_deg": [40, 100], "repeats": 1},
    "operating_region": {
      "polygon_m": [[-100, -100], [100, -100], [100, 100], [-100, 100]],
      "buffer_m": 25,
      "return_point_m": [0, -70]
    }
  })");
}

// Every error of the validation of `text`; a failure when it is accepted or throws anything else.
std::vector<FieldError> errors_of(const std::string& text, double vmax = 2.0) {
  try {
    parse_mission_config(text, vmax);
    ADD_FAILURE() << "accepted";
  } catch (const MissionConfigError& e) {
    for (const auto& f : e.errors())
      EXPECT_EQ(f.message.find("json.exception"), std::string::npos) << f.message;
    return e.errors();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than MissionConfigError: " << e.what();
  }
  return {};
}

bool names(const std::vector<FieldError>& errors, const std::string& field) {
  for (const auto& e : errors)
    if (e.field == field) return true;
  return false;
}

std::string with_number(const std::string& literal) {
  std::string text = base_mission().dump();
  const std::string at = "[0.5,1.0]";
  text.replace(text.find(at), at.size(), "[0.5," + literal + "]");
  return text;
}

}  // namespace

TEST(MissionLimits, ANumberTooLargeForADoubleIsAnErrorNamingItsField) {
  const auto errors = errors_of(with_number("1e400"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/turn_array/speeds_mps/1");
  EXPECT_NE(errors[0].message.find("range"), std::string::npos) << errors[0].message;
}

TEST(MissionLimits, TheThousandCubedMissionIsRefusedOnEveryAxis) {
  // The issue's 13 KB mission: 1000 speeds x 1000 heading changes x 1000 repeats.
  json d = base_mission();
  json speeds = json::array(), dheadings = json::array();
  for (int i = 1; i <= 1000; ++i) {
    speeds.push_back(0.002 * i);
    dheadings.push_back(0.18 * i);
  }
  d["turn_array"]["speeds_mps"] = speeds;
  d["turn_array"]["dheadings_deg"] = dheadings;
  d["turn_array"]["repeats"] = 1000;
  const auto errors = errors_of(d.dump());
  EXPECT_TRUE(names(errors, "/turn_array/speeds_mps"));
  EXPECT_TRUE(names(errors, "/turn_array/dheadings_deg"));
  EXPECT_TRUE(names(errors, "/turn_array/repeats"));
  // One error a list, not one an element: the report stays readable.
  EXPECT_LE(errors.size(), 4u);
}

TEST(MissionLimits, PlannedTurnsAreBoundedAcrossTheAxes) {
  // 20 speeds x 36 heading changes x 3 repeats = 2160 planned turns, each axis within its limit.
  json d = base_mission();
  json speeds = json::array(), dheadings = json::array();
  for (int i = 1; i <= 20; ++i)
    speeds.push_back(0.1 * i);
  for (int i = 1; i <= 36; ++i)
    dheadings.push_back(5 * i);
  d["turn_array"]["speeds_mps"] = speeds;
  d["turn_array"]["dheadings_deg"] = dheadings;
  d["turn_array"]["repeats"] = 3;
  const auto errors = errors_of(d.dump(), 2.5);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/turn_array");
  EXPECT_NE(errors[0].message.find("2160"), std::string::npos) << errors[0].message;
  // At the limit it is accepted: 20 x 36 x 2 = 1440.
  d["turn_array"]["repeats"] = 2;
  EXPECT_NO_THROW(parse_mission_config(d.dump(), 2.5));
}

TEST(MissionLimits, DuplicateSpeedsAndHeadingChangesAreRefused) {
  json d = base_mission();
  d["turn_array"]["speeds_mps"] = {1.0, 0.5, 1.0};
  d["turn_array"]["dheadings_deg"] = {40, 40.2, 100};
  const auto errors = errors_of(d.dump());
  EXPECT_TRUE(names(errors, "/turn_array/speeds_mps/2"));
  EXPECT_TRUE(names(errors, "/turn_array/dheadings_deg/1"));
  EXPECT_EQ(errors.size(), 2u);
}

// Values exactly the documented spacing apart are two cells, whatever their binary rounding:
// 1.15 - 1.1 is 0.04999999999999982 in doubles, 1.05 - 1.0 is 0.05000000000000004.
TEST(MissionLimits, ValuesExactlyTheSpacingApartAreAccepted) {
  for (const auto& speeds :
       {std::vector<double>{1.1, 1.15}, std::vector<double>{1.0, 1.05},
        std::vector<double>{0.15, 0.2, 0.25, 0.3}, std::vector<double>{1.7, 1.65}}) {
    json d = base_mission();
    d["turn_array"]["speeds_mps"] = speeds;
    d["turn_array"]["dheadings_deg"] = {40.1, 40.6, 100};
    d["turn_array"]["initial_yaw_rates_dps"] = {-0.7, -0.2, 0.3};
    EXPECT_NO_THROW(parse_mission_config(d.dump(), 2.0)) << json(speeds).dump();
  }
  json change = base_mission();
  change["turn_array"]["speed_changes"] = {{{"from_mps", 1.1}, {"to_mps", 1.15}},
                                           {{"from_mps", 1.15}, {"to_mps", 1.1}},
                                           {{"from_mps", 1.15}, {"to_mps", 1.2}}};
  EXPECT_NO_THROW(parse_mission_config(change.dump(), 2.0));
  // Closer than the spacing is still a duplicate.
  json close = base_mission();
  close["turn_array"]["speeds_mps"] = {1.1, 1.1499};
  const auto errors = errors_of(close.dump());
  EXPECT_TRUE(names(errors, "/turn_array/speeds_mps/1"));
  EXPECT_EQ(errors.size(), 1u);
}

// Regression: a 900 kB name was stored, and every list of missions then carried it.
TEST(MissionLimits, TheNameIsBoundedAndTheErrorSaysTheLimit) {
  json d = base_mission();
  d["name"] = std::string(900000, 'n');
  auto errors = errors_of(d.dump());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/name");
  EXPECT_NE(errors[0].message.find("at most 256 bytes"), std::string::npos) << errors[0].message;
  EXPECT_NE(errors[0].message.find("900000"), std::string::npos) << errors[0].message;
  d["name"] = std::string(kMaxMissionNameBytes + 1, 'n');
  EXPECT_TRUE(names(errors_of(d.dump()), "/name"));
  d["name"] = "";
  EXPECT_TRUE(names(errors_of(d.dump()), "/name"));
  d["name"] = std::string(kMaxMissionNameBytes, 'n');
  EXPECT_EQ(parse_mission_config(d.dump(), 2.0).name, std::string(256, 'n'));
}

TEST(MissionLimits, ARegionOfSixtyTwoThousandVerticesIsRefusedByItsCount) {
  // The issue's region: before the limit, the pairwise simplicity check took 48 s on it.
  json d = base_mission();
  json poly = json::array();
  const int n = 62000;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    poly.push_back({100.0 * std::cos(a), 100.0 * std::sin(a)});
  }
  d["operating_region"]["polygon_m"] = poly;
  const auto errors = errors_of(d.dump());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/operating_region/polygon_m");
  EXPECT_NE(errors[0].message.find("62000"), std::string::npos) << errors[0].message;
}

TEST(MissionLimits, ARegionAThousandKilometresWideIsRefused) {
  json d = base_mission();
  d["operating_region"]["polygon_m"] = {{-5e5, -5e5}, {5e5, -5e5}, {5e5, 5e5}, {-5e5, 5e5}};
  const auto errors = errors_of(d.dump());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/operating_region/polygon_m");
  // A region of the size the limit allows is accepted.
  d["operating_region"]["polygon_m"] = {{-5e3, -5e3}, {5e3, -5e3}, {5e3, 5e3}, {-5e3, 5e3}};
  EXPECT_NO_THROW(parse_mission_config(d.dump(), 2.0));
}

TEST(MissionLimits, DeepNestingIsAnErrorNotAStackOverflow) {
  std::string deep = "{\"name\": ";
  deep += std::string(100000, '[') + std::string(100000, ']') + "}";
  const auto errors = errors_of(deep);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].message.find("nested"), std::string::npos) << errors[0].message;
}

TEST(MissionLimits, ADuplicateKeyIsRefusedRatherThanTheLastOneWinning) {
  std::string text = base_mission().dump();
  text.insert(1, "\"name\":\"first\",");
  const auto errors = errors_of(text);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/name");
}

TEST(MissionLimits, ATopLevelNumberTooLargeForADoubleNamesTheDocument) {
  // Found by mission_config_fuzz: the error named an empty field.
  const auto errors = errors_of("2E335");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "/");
}
