// Small turns end to end: a mission of 10 deg turns on the simulated usim records each turn to
// its end now that completion is relative to the commanded change, where a fixed 5 deg threshold
// recorded about half of it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_monitor.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"

using namespace avk;
using kinematics::TurnStatus;

namespace {

struct Turns : mission::MissionObserver {
  std::vector<mission::TurnOutcome> ok;
  void on_turn(mission::TurnOutcome& o) override {
    if (o.status == TurnStatus::ok) ok.push_back(o);
  }
};

// 10 deg turns at two speeds, both sides, on the usim at rest at the return point; the
// constant_heading section as given.
std::vector<mission::TurnOutcome> fly(const std::string& constant_heading) {
  const std::string text = R"({
    "name": "small-turns",
    "turn_array": {"speeds_mps": [1.0, 1.5], "dheadings_deg": [10], "repeats": 2},
    "constant_heading": )" +
                           constant_heading + R"(,
    "operating_region": {"polygon_m": [[-100,-100],[100,-100],[100,100],[-100,100]],
                         "buffer_m": 25, "return_point_m": [0, -70]}})";
  const mission::MissionConfig config = mission::parse_mission_config(text, 2.0);
  sim::SimMissionOptions so;
  so.setup = sim::default_sim_setup("usim");
  so.setup.vehicle.id = "sim-usim";
  so.start = {0.0, -70.0, 0.0};
  so.max_duration_s = 3600.0;  // simulated
  sim::SimMission sim(so);
  mission::RunnerOptions ro;
  ro.vehicle_id = "sim-usim";
  mission::MissionRunner runner(config, sim.vehicle(), mission::plan_turns(config), ro);
  Turns turns;
  runner.add_observer(turns);
  sim::FastPacer pacer;
  sim.run(runner, pacer);
  EXPECT_TRUE(runner.finished());
  return turns.ok;
}

}  // namespace

TEST(SmallTurns, TenDegreeTurnsAreRecordedToWithinADegreeOfTheirGoal) {
  const auto turns = fly(R"({"completion_threshold_deg": 5})");  // fraction and floor default
  ASSERT_EQ(turns.size(), 4u);
  for (const auto& t : turns) {
    const auto& m = t.raw.meta();
    SCOPED_TRACE(::testing::Message()
                 << m.commanded_speed_mps << " m/s, goal " << m.goal_dheading_deg
                 << " deg, observed " << m.observed_dheading_deg << " deg");
    EXPECT_EQ(std::abs(m.goal_dheading_deg), 10.0);
    EXPECT_GE(std::abs(m.observed_dheading_deg), 9.0);  // measured 9.01-9.03
    EXPECT_GT(m.goal_dheading_deg * m.observed_dheading_deg, 0.0);
  }
}

TEST(SmallTurns, AFixedFiveDegreeThresholdEndedThemHalfWay) {
  // Fraction 1: the threshold is min(5, |goal|) = 5 deg for a 10 deg turn, as before the rule.
  const auto turns = fly(R"({"completion_threshold_deg": 5, "completion_fraction": 1})");
  ASSERT_EQ(turns.size(), 4u);
  for (const auto& t : turns)
    EXPECT_LT(std::abs(t.raw.meta().observed_dheading_deg), 6.0);  // measured 5.0-5.1
}
