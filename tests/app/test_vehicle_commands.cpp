// The station's vehicle commands through the use case: validation naming the field, hold, go to,
// return and stop on the vehicle loop (the simulator at 400x the wall clock), an attached mission
// aborted by a command, and the hold at the return point after a mission. Every wait is for a
// state, bounded at 60 s; nothing measures time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>

#include "app/context.hpp"
#include "app/missions.hpp"
#include "app/vehicle_commands.hpp"
#include "app/vehicles.hpp"
#include "sim/sim_config.hpp"
#include "support/recorded_mission.hpp"
#include "support/sim_vehicle_loop.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
using mission::HelmMode;
using mission::VehicleCommandKind;

// The station events the loop tells (vehicle commands have no mission to log them in).
class EventFeed final : public app::LiveFeed {
 public:
  void telemetry(const app::VehicleSnapshot&) override {}
  void station_event(double, mission::EventKind kind, const std::string& message) override {
    std::lock_guard lock(mutex_);
    events_.push_back({kind, message});
  }
  std::unique_ptr<mission::MissionObserver> follow(std::int64_t,
                                                   const mission::MissionRunner&) override {
    return std::make_unique<mission::MissionObserver>();
  }
  bool has(mission::EventKind kind, const std::string& part) const {
    std::lock_guard lock(mutex_);
    for (const auto& [k, m] : events_)
      if (k == kind && m.find(part) != std::string::npos) return true;
    return false;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<mission::EventKind, std::string>> events_;
};

class VehicleCommands : public ::testing::Test {
 protected:
  VehicleCommands() : ctx_(db_.path(), options(), &feed_) { ctx_.start(); }

  static app::VehicleLoopOptions options() { return avk::testing::sim_usim_loop_options(400.0); }

  app::VehicleSnapshot snapshot() { return *app::get_vehicle(ctx_, "sim-usim")->live; }
  // The snapshot once done(snapshot) holds, bounded at 60 s of wall clock.
  app::VehicleSnapshot wait_for(const std::function<bool(const app::VehicleSnapshot&)>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    app::VehicleSnapshot s = snapshot();
    while (!done(s) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      s = snapshot();
    }
    EXPECT_TRUE(done(s));
    return s;
  }
  static bool holding(const app::VehicleSnapshot& s) { return s.helm_mode == HelmMode::holding; }
  static double distance_m(const app::VehicleSnapshot& s, kinematics::Point p) {
    return kinematics::distance_m({s.nav->x_m, s.nav->y_m}, p);
  }

  app::Error error_of(const app::VehicleCommandRequest& r, const std::string& vid = "sim-usim") {
    const auto got = app::command_vehicle(ctx_, vid, r);
    EXPECT_FALSE(got);
    return got ? app::Error{} : got.error();
  }

  avk::testing::TempDb db_{"avk_app_vehicle_commands"};
  EventFeed feed_;
  app::Context ctx_;
};

app::VehicleCommandRequest request(VehicleCommandKind kind) {
  app::VehicleCommandRequest r;
  r.kind = kind;
  return r;
}

TEST_F(VehicleCommands, ValidationErrorsNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto r = request(VehicleCommandKind::hold);
  r.radius_m = 0.0;
  EXPECT_EQ(error_of(r).field, "radius_m");
  r.radius_m = mission::kMaxHoldRadiusM + 1.0;
  EXPECT_EQ(error_of(r).field, "radius_m");
  r.radius_m = nan;
  EXPECT_EQ(error_of(r).field, "radius_m");
  r = request(VehicleCommandKind::hold);
  r.x_m = nan;
  r.y_m = 0.0;
  EXPECT_EQ(error_of(r).field, "x_m");
  r.x_m = 10.0;
  r.y_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of(r).field, "y_m");
  r.y_m = app::kMaxCommandCoordinateM * 2.0;
  EXPECT_EQ(error_of(r).field, "y_m");
  r.y_m.reset();
  EXPECT_EQ(error_of(r).field, "y_m");  // x without y
  const auto go = request(VehicleCommandKind::go_to);
  const app::Error no_point = error_of(go);
  EXPECT_EQ(no_point.code, app::ErrorCode::invalid_argument);
  EXPECT_EQ(no_point.field, "x_m");
  auto fast = request(VehicleCommandKind::go_to);
  fast.x_m = 0.0;
  fast.y_m = 0.0;
  fast.speed_mps = ctx_.vehicle_loops().front()->info().max_speed_mps + 0.1;
  const app::Error too_fast = error_of(fast);
  EXPECT_EQ(too_fast.field, "speed_mps");
  EXPECT_NE(too_fast.message.find("top speed"), std::string::npos) << too_fast.message;
  fast.speed_mps = -1.0;
  EXPECT_EQ(error_of(fast).field, "speed_mps");
  EXPECT_EQ(error_of(request(VehicleCommandKind::stop), "nobody").code, app::ErrorCode::not_found);
  // No mission has run yet: nowhere to return to without a point.
  EXPECT_EQ(error_of(request(VehicleCommandKind::return_to)).code, app::ErrorCode::conflict);
  // Nothing was applied.
  EXPECT_FALSE(snapshot().command);
}

TEST_F(VehicleCommands, HoldGoToAndStopShowInTheSnapshotAndAreLogged) {
  auto hold = request(VehicleCommandKind::hold);
  hold.radius_m = 4.0;
  const auto held = app::command_vehicle(ctx_, "sim-usim", hold);
  ASSERT_TRUE(held) << held.error().message;
  auto s = wait_for([](const auto& s) { return s.command && s.command->command.point; });
  EXPECT_EQ(s.command->command.kind, VehicleCommandKind::hold);
  EXPECT_EQ(s.command->command.radius_m, 4.0);
  EXPECT_LT(kinematics::distance_m(*s.command->command.point, {0.0, -70.0}), 2.0);  // here
  EXPECT_FALSE(s.mission_id);
  wait_for(holding);
  EXPECT_TRUE(feed_.has(mission::EventKind::vehicle_command, "hold at (0.0"));

  auto go = request(VehicleCommandKind::go_to);
  go.x_m = 40.0;
  go.y_m = -20.0;
  go.speed_mps = 1.5;
  ASSERT_TRUE(app::command_vehicle(ctx_, "sim-usim", go));
  s = wait_for([](const auto& s) { return s.helm_mode == HelmMode::transiting; });
  ASSERT_TRUE(s.command);
  EXPECT_EQ(s.command->command.kind, VehicleCommandKind::go_to);
  s = wait_for(holding);
  EXPECT_LE(distance_m(s, {40.0, -20.0}), mission::kDefaultHoldRadiusM + 1.0);
  EXPECT_TRUE(feed_.has(mission::EventKind::vehicle_command, "go_to (40.0, -20.0) at 1.50 m/s"));
  EXPECT_TRUE(feed_.has(mission::EventKind::arrived, "arrived at (40.0, -20.0)"));

  ASSERT_TRUE(app::command_vehicle(ctx_, "sim-usim", request(VehicleCommandKind::stop)));
  s = wait_for([](const auto& s) {
    return s.helm_mode == HelmMode::stopped && s.nav && std::abs(s.nav->speed_mps) < 0.05;
  });
  EXPECT_EQ(s.desired_speed_mps, 0.0);
  EXPECT_TRUE(feed_.has(mission::EventKind::vehicle_command, "all stop"));
}

TEST_F(VehicleCommands, AMissionsEndHoldsAtItsReturnPointAndACommandAbortsAMission) {
  const auto id = app::start_mission(ctx_, "sim-usim", avk::testing::kSmallMission);
  ASSERT_TRUE(id) << id.error().message;
  // Its end: the vehicle holds at the return point (0, -70) instead of drifting.
  auto s = wait_for([](const auto& s) { return !s.mission_id && s.command; });
  EXPECT_EQ(app::mission_report(ctx_, *id)->summary.status, app::MissionStatus::done);
  EXPECT_EQ(s.command->command.kind, VehicleCommandKind::return_to);
  EXPECT_EQ(s.command->command.point, (kinematics::Point{0.0, -70.0}));
  s = wait_for(holding);
  EXPECT_LE(distance_m(s, {0.0, -70.0}), mission::kDefaultHoldRadiusM + 1.0);
  EXPECT_TRUE(feed_.has(mission::EventKind::vehicle_command, "mission " + std::to_string(*id)));

  // `return` without a point now knows where to go.
  auto go = request(VehicleCommandKind::go_to);
  go.x_m = 30.0;
  go.y_m = 0.0;
  ASSERT_TRUE(app::command_vehicle(ctx_, "sim-usim", go));
  const auto back = app::command_vehicle(ctx_, "sim-usim", request(VehicleCommandKind::return_to));
  ASSERT_TRUE(back) << back.error().message;
  s = wait_for([](const auto& s) {
    return s.command && s.command->command.kind == VehicleCommandKind::return_to;
  });
  EXPECT_EQ(s.command->command.point, (kinematics::Point{0.0, -70.0}));

  // A command while a mission runs aborts it first, and its log says why.
  const auto second = app::start_mission(ctx_, "sim-usim", avk::testing::kSmallMission);
  ASSERT_TRUE(second) << second.error().message;
  wait_for([&](const auto& s) { return s.mission_id == *second; });
  ASSERT_TRUE(app::command_vehicle(ctx_, "sim-usim", request(VehicleCommandKind::stop)));
  s = wait_for([](const auto& s) { return s.helm_mode == HelmMode::stopped; });
  EXPECT_FALSE(s.mission_id);
  EXPECT_EQ(app::mission_report(ctx_, *second)->summary.status, app::MissionStatus::aborted);
  const auto events = app::mission_events(ctx_, *second, 0, 1000);
  ASSERT_TRUE(events);
  bool logged = false;
  for (const auto& e : events->items)
    logged = logged || e.message.find("operator's command: all stop") != std::string::npos;
  EXPECT_TRUE(logged);
}

}  // namespace
