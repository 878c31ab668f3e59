// The helm's tick on a scaled wall clock (vehicles on the network): its rate, the stop flag and
// the time limit. The clock runs 100x or 1000x, so ten seconds of mission take at most 0.1 s.
// A loaded machine may skip ticks (the loop does not catch up), so the tests bound the tick count
// from above only and never assert how much wall or mission time a step took.
#include <gtest/gtest.h>

#include <atomic>

#include "mission/helm_loop.hpp"
#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"

namespace {

using namespace avk;

// A vehicle that never reports navigation: the runner ticks and waits.
class SilentVehicle final : public vehicle::Vehicle {
 public:
  const vehicle::VehicleInfo& info() const override { return info_; }
  std::vector<vehicle::NavSample> take_nav() override { return {}; }
  std::optional<vehicle::NavSample> last_nav() const override { return std::nullopt; }
  vehicle::LinkState link_state(double) const override { return vehicle::LinkState::disconnected; }
  void command(const vehicle::DesiredCommand&) override {}
  void all_stop(double) override { ++all_stops; }
  std::optional<vehicle::DesiredCommand> last_command() const override { return std::nullopt; }
  std::optional<vehicle::ActuatorCommand> last_actuators() const override { return std::nullopt; }
  int all_stops = 0;

 private:
  vehicle::VehicleInfo info_{"silent", "fake", 2.0, {}};
};

mission::MissionConfig config() {
  mission::MissionConfig c;
  c.name = "loop";
  c.turn_array.speeds_mps = {1.0};
  c.turn_array.dheadings_deg = {90};
  c.region.polygon = {{-50, -50}, {50, -50}, {50, 50}, {-50, 50}};
  c.region.buffer_m = 10;
  return c;
}

TEST(HelmLoop, TicksAtTheHelmRateUntilTheTimeLimit) {
  SilentVehicle v;
  const auto c = config();
  mission::MissionRunner runner(c, v, mission::plan_turns(c), {});
  const vehicle::ScaledClock clock(100.0, 50.0);
  int ticks = 0;
  double last = 0.0;
  bool monotonic = true;
  const auto r = mission::run_helm_loop(runner, clock, 4.0, 10.0, nullptr, [&](double now) {
    monotonic = monotonic && now >= last;
    last = now;
    ++ticks;
  });
  EXPECT_TRUE(r.horizon_reached);
  EXPECT_FALSE(r.stopped);
  EXPECT_GE(r.start_time_s, 50.0);
  EXPECT_GE(r.end_time_s - r.start_time_s, 10.0);
  EXPECT_EQ(*runner.state(), mission::MissionState::interrupted);
  EXPECT_TRUE(monotonic);
  // 4 Hz for 10 s: 40 ticks, never more; fewer only if the machine was too slow to keep 100x.
  EXPECT_LE(ticks, 41);
  EXPECT_GE(ticks, 1);
}

TEST(HelmLoop, TimeTheLoopWasStarvedOfIsNotChargedToTheLimit) {
  SilentVehicle v;
  const auto c = config();
  mission::MissionRunner runner(c, v, mission::plan_turns(c), {});
  const vehicle::ScaledClock clock(1000.0);
  int ticks = 0;
  double stalled_from = 0.0, stalled_to = 0.0;
  // The third tick holds the thread for 30 s of the clock (30 ms of wall time): a stall that
  // takes three times the whole 10 s limit.
  const auto r = mission::run_helm_loop(runner, clock, 4.0, 10.0, nullptr, [&](double now) {
    if (++ticks != 3) return;
    stalled_from = now;
    while (clock.now_s() < now + 30.0) {
    }
    stalled_to = clock.now_s();
  });
  EXPECT_TRUE(r.horizon_reached);
  // The stall less the one tick it replaced is not charged; the limit still ends the loop.
  EXPECT_GE(r.starved_s, stalled_to - stalled_from - 0.25 - 1e-9);
  EXPECT_GE(r.end_time_s - r.start_time_s, 10.0 + r.starved_s - 1e-9);
  EXPECT_GT(ticks, 3);
  EXPECT_EQ(*runner.state(), mission::MissionState::interrupted);
}

TEST(HelmLoop, TheStopFlagInterruptsAtTheNextTick) {
  SilentVehicle v;
  const auto c = config();
  mission::MissionRunner runner(c, v, mission::plan_turns(c), {});
  const vehicle::ScaledClock clock(1000.0);
  std::atomic<bool> stop{false};
  int ticks = 0;
  // A horizon of 10^6 s (1000 s of wall time): only the flag can end this loop.
  const auto r = mission::run_helm_loop(runner, clock, 4.0, 1e6, &stop, [&](double) {
    if (++ticks == 5) stop = true;
  });
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.horizon_reached);
  EXPECT_EQ(ticks, 5);  // the tick after the flag went up interrupted without running the hook
  EXPECT_EQ(*runner.state(), mission::MissionState::interrupted);
}

TEST(HelmLoop, RejectsARateThatIsNotPositive) {
  SilentVehicle v;
  const auto c = config();
  mission::MissionRunner runner(c, v, mission::plan_turns(c), {});
  const vehicle::ScaledClock clock(1000.0);
  EXPECT_THROW(mission::run_helm_loop(runner, clock, 0.0, 10.0), std::invalid_argument);
}

}  // namespace
