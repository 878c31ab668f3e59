// Mission input limits at the station: a mission too large to plan, or with a number JSON cannot
// hold, is a 422 naming the field, and a start that fails leaves no mission row behind.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "app/context.hpp"
#include "app/mission_plans.hpp"
#include "app/store_access.hpp"
#include "mission/mission_config.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/sim_station.hpp"
#include "support/temp_db.hpp"

using nlohmann::json;

namespace {

constexpr const char* kToken = "test-token-for-mission-limits";

json mission(json speeds, json dheadings, int repeats) {
  return {{"name", "limits"},
          {"turn_array",
           {{"speeds_mps", std::move(speeds)},
            {"dheadings_deg", std::move(dheadings)},
            {"repeats", repeats}}},
          {"operating_region",
           {{"polygon_m", {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}},
            {"buffer_m", 25},
            {"return_point_m", {0, -70}}}}};
}

// 20 speeds x 36 heading changes x 1000 repeats: 720,000 planned turns, which the validation
// let through (each axis was unbounded or allowed up to 1000) and the start then stored.
std::string oversized_mission() {
  json speeds = json::array(), dheadings = json::array();
  for (int i = 1; i <= 20; ++i)
    speeds.push_back(0.1 * i);
  for (int i = 1; i <= 36; ++i)
    dheadings.push_back(5 * i);
  return mission(speeds, dheadings, 1000).dump();
}

}  // namespace

TEST(MissionLimitsStore, AMissionTooLargeToPlanLeavesNoRowBehind) {
  avk::testing::TempDb path{"avk_mission_limits"};
  avk::app::Context ctx(path.path());
  avk::store::Store& db = avk::app::store_of(ctx);
  const avk::vehicle::VehicleInfo info{"sim-usim", "usim", 2.0, std::nullopt};
  const auto refused = avk::app::create_mission_plan(ctx, oversized_mission(), info);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, avk::app::ErrorCode::invalid_argument);
  EXPECT_FALSE(refused.error().fields.empty());
  EXPECT_TRUE(db.missions().list().empty());
  // A mission within the limits is stored with its plan.
  const auto plan =
      avk::app::create_mission_plan(ctx, mission({0.5, 1.0}, {40, 100}, 2).dump(), info);
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->tasks.size(), 8u);
  EXPECT_EQ(db.missions().list().size(), 1u);
}

class MissionLimitsApi : public ::testing::Test {
 protected:
  void SetUp() override {
    station_ = std::make_unique<avk::server::Station>(
        avk::testing::sim_station_options(db_.path(), kToken, 50.0), hub_);
    station_->start();
  }
  void TearDown() override { station_.reset(); }

  avk::server::ApiResponse call(const std::string& method, const std::string& path,
                                const std::string& body = {}) {
    avk::server::ApiRequest r;
    r.method = method;
    r.path = path;
    r.body = body;
    r.content_type = "application/json";
    r.authorization = std::string("Bearer ") + kToken;
    return station_->handle(r);
  }

  avk::testing::TempDb db_{"avk_mission_limits_api"};
  avk::server::StreamHub hub_;
  std::unique_ptr<avk::server::Station> station_;
};

TEST_F(MissionLimitsApi, ANumberTooLargeForADoubleIsA422NamingTheField) {
  std::string text = mission({0.5, 1.0}, {40, 100}, 1).dump();
  const std::string at = "[0.5,1.0]";
  text.replace(text.find(at), at.size(), "[0.5,1e400]");
  const auto r = call("POST", "/api/v1/vehicles/sim-usim/missions", text);
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(r.body.find("json.exception"), std::string::npos) << r.body;
  const json problem = json::parse(r.body);
  ASSERT_TRUE(problem.contains("errors")) << r.body;
  EXPECT_EQ(problem["errors"][0]["field"], "/turn_array/speeds_mps/1");
  EXPECT_EQ(json::parse(call("GET", "/api/v1/missions").body).size(), 0u);
}

TEST_F(MissionLimitsApi, AMissionTooLargeToPlanIsA422AndNothingIsStored) {
  const auto r = call("POST", "/api/v1/vehicles/sim-usim/missions", oversized_mission());
  EXPECT_EQ(r.status, 422) << r.body;
  const json problem = json::parse(r.body);
  ASSERT_TRUE(problem.contains("errors")) << r.body;
  EXPECT_EQ(problem["errors"][0]["field"], "/turn_array/repeats");
  EXPECT_EQ(json::parse(call("GET", "/api/v1/missions").body).size(), 0u);
}

// Regression: a 900 kB mission name was stored, and GET /missions then answered 901 KB.
TEST_F(MissionLimitsApi, ANameTooLongIsA422NamingTheFieldAndTheLimit) {
  json m = mission({0.5, 1.0}, {40, 100}, 1);
  m["name"] = std::string(900000, 'n');
  const auto r = call("POST", "/api/v1/vehicles/sim-usim/missions", m.dump());
  EXPECT_EQ(r.status, 422) << r.body.substr(0, 300);
  EXPECT_LT(r.body.size(), 2000u) << "the answer quotes the name";
  const json problem = json::parse(r.body);
  ASSERT_TRUE(problem.contains("errors")) << r.body;
  EXPECT_EQ(problem["errors"][0]["field"], "/name");
  EXPECT_NE(problem["errors"][0]["message"].get<std::string>().find("at most 256 bytes"),
            std::string::npos)
      << problem["errors"];
  EXPECT_EQ(json::parse(call("GET", "/api/v1/missions").body).size(), 0u);
}
