// The mission recorder stores every turn the runner ends, whatever its status: on the simulator's
// scheduler (no wall clock, no load dependence) with each way a turn can fail forced at a chosen
// moment of the mission clock: a navigation outage that makes the link stale (aborted), a shorter
// one that leaves a gap in the turn (rejected), an operator's pause (aborted).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "app/context.hpp"
#include "app/mission_plans.hpp"
#include "app/mission_recorder.hpp"
#include "app/store_access.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"
#include "store/store.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
using kinematics::TurnStatus;

// What the runner reported, in order, per status.
class Reported final : public mission::MissionObserver {
 public:
  void on_turn_started(const mission::TurnTask&, const mission::RunningTurn& turn) override {
    starts.push_back(turn.start.t_s);
  }
  void on_turn(mission::TurnOutcome& t) override { reasons[t.status].push_back(t.reason); }
  std::vector<double> starts;
  std::map<TurnStatus, std::vector<std::string>> reasons;
};

constexpr const char* kMission = R"({
  "name": "recorder",
  "turn_array": {"speeds_mps": [1.0, 1.5], "dheadings_deg": [40, 90]},
  "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                       "buffer_m": 25, "return_point_m": [0, -70]}})";

TEST(MissionRecorder, EveryAbortedAndRejectedTurnIsStoredWithItsReason) {
  avk::testing::TempDb db_file("avk_recorder");
  app::Context ctx(db_file.path());
  store::Store& db = app::store_of(ctx);
  sim::SimMissionOptions so;
  so.setup = sim::default_sim_setup("usim");
  const auto config = mission::parse_mission_config(kMission, 2.0);
  so.start = app::start_pose(config);
  sim::SimMission sim(so);
  const app::MissionPlan plan =
      app::create_mission_plan(ctx, kMission, sim.vehicle().info()).value();

  mission::RunnerOptions ro;
  ro.vehicle_id = sim.vehicle().info().id;
  // Shorter than the 2 s after which the link is stale, so a 0.8 s outage is a gap in the turn
  // (rejected) and a 3 s one is a lost link (aborted).
  ro.max_sample_gap_s = 0.5;
  mission::MissionRunner runner(plan.config, sim.vehicle(), plan.tasks, ro);
  Reported reported;
  {
    app::MissionRecorder recorder(db, plan.mission_id);
    runner.add_observer(recorder);
    runner.add_observer(reported);
    sim::FastPacer pacer;
    bool paused = false;
    sim.run(runner, pacer, nullptr, [&](double now) {
      if (reported.starts.empty()) return;
      const double since = now - reported.starts.back();
      switch (reported.starts.size()) {
        case 1:  // the link goes stale in the middle of the first turn
          sim.sim_vehicle().set_nav_outage(since >= 1.0 && since < 4.0);
          break;
        case 2:  // a gap in the second, too short to lose the link
          sim.sim_vehicle().set_nav_outage(since >= 0.3 && since < 1.1);
          break;
        case 3:  // the operator pauses the third, and resumes 5 s later
          if (!paused && since >= 0.5) {
            paused = runner.pause(now);
          } else if (paused && since >= 5.5 && runner.mode() == mission::HelmMode::paused) {
            runner.resume(now);
          }
          break;
        default:
          sim.sim_vehicle().set_nav_outage(false);
      }
    });
    recorder.flush();
  }
  ASSERT_EQ(runner.state(), mission::MissionState::done);
  const auto& aborted = reported.reasons[TurnStatus::aborted];
  const auto& rejected = reported.reasons[TurnStatus::rejected];
  ASSERT_EQ(aborted.size(), 2u);
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_EQ(aborted[0], "navigation lost during the turn");
  EXPECT_EQ(aborted[1], "paused by operator");
  EXPECT_NE(rejected[0].find("navigation gap"), std::string::npos) << rejected[0];
  EXPECT_EQ(reported.reasons[TurnStatus::ok].size(), 4u);

  // The store holds each of them, with the same status and reason, in the same order.
  for (const TurnStatus status : {TurnStatus::ok, TurnStatus::aborted, TurnStatus::rejected}) {
    store::TurnFilter f;
    f.mission_id = plan.mission_id;
    f.status = status;
    f.limit = 1000;
    std::vector<std::string> stored;
    for (const auto& row : db.turns().list(f))
      stored.push_back(row.reason);
    EXPECT_EQ(stored, reported.reasons[status]) << kinematics::to_string(status);
  }
  std::int64_t n_aborted = 0, n_rejected = 0;
  for (const auto& c : db.missions().cell_stats(plan.mission_id)) {
    n_aborted += c.n_aborted;
    n_rejected += c.n_rejected;
  }
  EXPECT_EQ(n_aborted, 2);
  EXPECT_EQ(n_rejected, 1);
}

}  // namespace
