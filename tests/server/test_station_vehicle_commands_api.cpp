// The vehicle commands over the REST API: the token, problems naming the field, a body that is
// optional, the command in GET /vehicles/{vid}, and the hold at the return point after a mission.
#include <gtest/gtest.h>

#include "server/station_api_fixture.hpp"

namespace {

using namespace avk::testing::station_api;

class VehicleCommandsApi : public StationApi {
 protected:
  // The vehicle once done(vehicle) holds, bounded at 60 s of wall clock.
  template <class F>
  json wait_for_vehicle(F done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    json v = body(call(get("/api/v1/vehicles/sim-usim")));
    while (!done(v) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      v = body(call(get("/api/v1/vehicles/sim-usim")));
    }
    EXPECT_TRUE(done(v)) << v.dump();
    return v;
  }
};

TEST_F(VehicleCommandsApi, EveryCommandNeedsTheToken) {
  for (const char* c : {"hold", "go-to", "return", "stop"}) {
    const ApiResponse r = call(post(std::string("/api/v1/vehicles/sim-usim/") + c, "{}", ""));
    EXPECT_EQ(r.status, 401) << c;
    EXPECT_EQ(r.content_type, "application/problem+json") << c;
  }
  EXPECT_TRUE(body(call(get("/api/v1/vehicles/sim-usim")))["command"].is_null());
}

TEST_F(VehicleCommandsApi, ProblemsNameTheField) {
  const auto problem = [&](const std::string& path, const std::string& doc) {
    const ApiResponse r = call(post("/api/v1/vehicles/sim-usim/" + path, doc));
    EXPECT_EQ(r.status, 422) << path << " " << doc << ": " << r.body;
    return body(r);
  };
  EXPECT_EQ(problem("hold", R"({"radius_m":0})")["pointer"], "/radius_m");
  EXPECT_EQ(problem("hold", R"({"radius_m":"5"})")["pointer"], "/radius_m");
  EXPECT_EQ(problem("hold", R"({"radius":5})")["pointer"], "/radius");  // misspelt: not ignored
  EXPECT_EQ(problem("hold", R"({"x_m":1e9,"y_m":0})")["pointer"], "/x_m");
  EXPECT_EQ(problem("hold", R"({"x_m":3})")["pointer"], "/y_m");
  EXPECT_EQ(problem("go-to", "{}")["pointer"], "/x_m");
  EXPECT_EQ(problem("go-to", R"({"x_m":0,"y_m":0,"speed_mps":99})")["pointer"], "/speed_mps");
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/hold", "[1]")).status, 400);
  EXPECT_EQ(call(post("/api/v1/vehicles/nobody/stop", "")).status, 404);
  // No mission has run: return needs a point.
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/return", "")).status, 409);
}

TEST_F(VehicleCommandsApi, HoldGoToAndStopShowInTheVehicle) {
  ApiResponse r = call(post("/api/v1/vehicles/sim-usim/hold", ""));  // no body: here
  ASSERT_EQ(r.status, 200) << r.body;
  json v = wait_for_vehicle([](const json& v) { return v["helm_mode"] == "HOLDING"; });
  EXPECT_EQ(v["command"]["kind"], "hold");
  EXPECT_EQ(v["command"]["radius_m"], 5.0);
  EXPECT_TRUE(v["command"]["x_m"].is_number());
  EXPECT_TRUE(v["mission_id"].is_null());

  r = call(post("/api/v1/vehicles/sim-usim/go-to",
                R"({"x_m":30,"y_m":-40,"speed_mps":1.5,"radius_m":6})"));
  ASSERT_EQ(r.status, 200) << r.body;
  v = wait_for_vehicle(
      [](const json& v) { return v["command"]["kind"] == "go_to" && v["helm_mode"] == "HOLDING"; });
  EXPECT_EQ(v["command"]["x_m"], 30.0);
  EXPECT_EQ(v["command"]["y_m"], -40.0);
  EXPECT_EQ(v["command"]["speed_mps"], 1.5);
  EXPECT_LE(v["command"]["distance_m"].get<double>(), 7.0);

  ASSERT_EQ(call(post("/api/v1/vehicles/sim-usim/stop", "")).status, 200);
  v = wait_for_vehicle([](const json& v) { return v["helm_mode"] == "STOPPED"; });
  EXPECT_EQ(v["command"]["kind"], "stop");
  EXPECT_EQ(v["desired_speed_mps"], 0.0);
}

TEST_F(VehicleCommandsApi, AfterAMissionTheVehicleHoldsAtItsReturnPoint) {
  const std::int64_t id = start_mission();
  wait_for_vehicle([&](const json& v) {
    return v["mission_id"].is_null() && v["command"].is_object() && v["helm_mode"] == "HOLDING";
  });
  const json m = body(call(get("/api/v1/missions/" + std::to_string(id))));
  EXPECT_EQ(m["status"], "done");
  const json v = body(call(get("/api/v1/vehicles/sim-usim")));
  EXPECT_EQ(v["command"]["kind"], "return");
  EXPECT_EQ(v["command"]["x_m"], 0.0);
  EXPECT_EQ(v["command"]["y_m"], -70.0);
  // `return` now knows where to go without a point.
  ASSERT_EQ(call(post("/api/v1/vehicles/sim-usim/return", "")).status, 200);
}

}  // namespace
