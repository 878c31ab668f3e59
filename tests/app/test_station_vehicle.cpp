// Missions on the station's own vehicle through the use cases: start, the live report, pause,
// resume and abort, with the vehicle loop on the simulator at 400x the wall clock. Every wait is
// for a state, bounded at 60 s; nothing measures time.
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <thread>

#include "app/context.hpp"
#include "app/missions.hpp"
#include "app/vehicles.hpp"
#include "kinematics/angles.hpp"
#include "sim/sim_config.hpp"
#include "support/recorded_mission.hpp"
#include "support/sim_vehicle_loop.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

class StationVehicle : public ::testing::Test {
 protected:
  StationVehicle() : ctx_(db_.path(), options()) { ctx_.start(); }

  static app::VehicleLoopOptions options() { return avk::testing::sim_usim_loop_options(400.0); }

  // The report once its status is one of `states`.
  app::MissionReport wait_for(std::int64_t id, const std::set<std::string>& states) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    auto r = app::mission_report(ctx_, id);
    while (r && !states.count(app::status_text(*r)) &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      r = app::mission_report(ctx_, id);
    }
    EXPECT_TRUE(r && states.count(app::status_text(*r))) << (r ? app::status_text(*r) : "none");
    return r ? *r : app::MissionReport{};
  }

  avk::testing::TempDb db_{"avk_app_station"};
  app::Context ctx_;
};

TEST_F(StationVehicle, AMissionStartsPausesResumesAndAborts) {
  const auto id = app::start_mission(ctx_, "sim-usim", avk::testing::kSmallMission);
  ASSERT_TRUE(id) << id.error().message;
  // A second one while it runs: a conflict naming the running mission, nothing stored.
  const auto second = app::start_mission(ctx_, "sim-usim", avk::testing::kSmallMission);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, app::ErrorCode::conflict);
  EXPECT_EQ(second.error().mission_id, *id);
  EXPECT_EQ(app::list_missions(ctx_, std::nullopt).size(), 1u);
  // Another vehicle is not this station's.
  EXPECT_EQ(app::start_mission(ctx_, "other", avk::testing::kSmallMission).error().code,
            app::ErrorCode::conflict);

  const auto running = wait_for(*id, {"running"});
  EXPECT_TRUE(running.live);
  EXPECT_EQ(running.cells.size(), 4u);
  const auto vehicle = app::get_vehicle(ctx_, "sim-usim");
  ASSERT_TRUE(vehicle && vehicle->live);

  const auto paused = app::command_mission(ctx_, *id, app::MissionCommand::pause);
  ASSERT_TRUE(paused) << paused.error().message;
  const auto p = wait_for(*id, {"paused"});
  EXPECT_EQ(p.helm_mode, mission::HelmMode::paused);
  ASSERT_TRUE(app::command_mission(ctx_, *id, app::MissionCommand::resume));
  wait_for(*id, {"running"});
  ASSERT_TRUE(app::command_mission(ctx_, *id, app::MissionCommand::abort));
  const auto aborted = wait_for(*id, {"aborted"});
  EXPECT_EQ(aborted.summary.mission.id, *id);
  // Once the loop has let it go, the stored status answers and pause is a conflict.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (ctx_.vehicle_loops().front()->attached_mission() &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_FALSE(ctx_.vehicle_loops().front()->attached_mission());
  EXPECT_EQ(app::mission_report(ctx_, *id)->summary.status, app::MissionStatus::aborted);
  EXPECT_EQ(app::command_mission(ctx_, *id, app::MissionCommand::pause).error().code,
            app::ErrorCode::conflict);
}

// A page opened mid-turn reads the turn from the report: while the helm is TURNING the
// live report names the turn as commanded; paused, it has none.
TEST_F(StationVehicle, TheLiveReportCarriesTheTurnUnderWay) {
  const auto id = app::start_mission(ctx_, "sim-usim", avk::testing::kSmallMission);
  ASSERT_TRUE(id) << id.error().message;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  app::MissionReport r;
  for (;;) {
    const auto got = app::mission_report(ctx_, *id);
    ASSERT_TRUE(got);
    r = *got;
    if (r.helm_mode == mission::HelmMode::turning) break;
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "no TURNING seen";
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(r.live);
  ASSERT_TRUE(r.running_turn.has_value());
  const mission::RunningTurn& t = *r.running_turn;
  EXPECT_NEAR(kinematics::wrap360_deg(t.start.heading_deg + t.dheading_deg), t.goal_heading_deg,
              1e-9);
  EXPECT_TRUE(std::abs(std::abs(t.dheading_deg) - 40.0) < 1e-9 ||
              std::abs(std::abs(t.dheading_deg) - 90.0) < 1e-9)
      << t.dheading_deg;
  EXPECT_TRUE(t.speed_mps == 1.0 || t.speed_mps == 1.5) << t.speed_mps;
  EXPECT_GE(t.attempt, 1);

  ASSERT_TRUE(app::command_mission(ctx_, *id, app::MissionCommand::pause));
  const auto p = wait_for(*id, {"paused"});
  EXPECT_FALSE(p.running_turn.has_value());
  ASSERT_TRUE(app::command_mission(ctx_, *id, app::MissionCommand::abort));
  wait_for(*id, {"aborted"});
}

}  // namespace
