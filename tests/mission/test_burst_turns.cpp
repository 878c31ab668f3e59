// Turns recorded from navigation that a link delivered in bursts: the M200 driver's samples (a
// session fed 2 to 20 lines a read, many reads late) go to the mission's turn monitor, and every
// turn completes and passes the checks a turn must pass to be stored as ok.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "mission/turn_checks.hpp"
#include "mission/turn_monitor.hpp"
#include "support/frontseat_bursts.hpp"
#include "vehicle/m200_session.hpp"

namespace {

using namespace avk;

struct PlannedTurn {
  double start_s;
  double dheading_deg;
};

// A boat at 1 m/s that holds its heading and turns at 12 deg/s when a turn starts; 5 Hz poses.
std::vector<avk::testing::FrontseatLine> boat_turning(const std::vector<PlannedTurn>& turns,
                                                      double end_s, const vehicle::LatLon& datum) {
  constexpr double kDt = 0.2, kRateDps = 12.0, kSpeedMps = 1.0;
  std::vector<avk::testing::FrontseatLine> out;
  double x = 0.0, y = 0.0, heading = 0.0, remaining = 0.0;
  std::size_t next = 0;
  for (double t = 0.0; t < end_s; t += kDt) {
    if (next < turns.size() && t >= turns[next].start_s - 1e-9)
      remaining = turns[next++].dheading_deg;
    const double step = std::copysign(std::min(std::abs(remaining), kRateDps * kDt), remaining);
    for (auto& l : avk::testing::navigation_lines({t, x, y, heading, kSpeedMps, step / kDt}, datum))
      out.push_back(std::move(l));
    heading = kinematics::wrap360_deg(heading + step);
    remaining -= step;
    x += kSpeedMps * kDt * std::sin(kinematics::deg_to_rad(heading));
    y += kSpeedMps * kDt * std::cos(kinematics::deg_to_rad(heading));
  }
  return out;
}

TEST(BurstTurns, EveryTurnFromBurstDeliveredNavigationCompletes) {
  const std::vector<PlannedTurn> turns = {{5, 30},   {20, -60}, {35, 90},  {55, -120},
                                          {75, 150}, {95, -20}, {110, 45}, {125, -170}};
  vehicle::M200Config config;
  const auto lines = boat_turning(turns, 150.0, config.datum);
  const mission::CompletionRule rule;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    vehicle::M200Session session(config);
    session.on_connected(0.0);
    std::vector<vehicle::NavSample> nav;
    for (const auto& r : avk::testing::in_bursts(lines, seed, 0.05, 1.0)) {
      session.on_received(r.bytes, r.read_s);
      for (const auto& n : session.take_nav())
        nav.push_back(n);
    }
    int completed = 0;
    std::size_t i = 0;
    for (const PlannedTurn& turn : turns) {
      // The helm commands the turn at the first sample at or after its start.
      while (i < nav.size() && nav[i].t_s < turn.start_s + 0.05 - 1e-6)
        ++i;
      ASSERT_LT(i, nav.size());
      mission::TurnMonitor monitor(nav[i], 1.0, turn.dheading_deg, rule);
      while (++i < nav.size() && monitor.update(nav[i]) == mission::Completion::none) {
      }
      ASSERT_NE(monitor.completion(), mission::Completion::none) << turn.dheading_deg;
      const auto raw = monitor.build("m200", "bursts");
      const auto anomaly = mission::turn_anomaly(raw, {rule, 2.0});
      EXPECT_FALSE(anomaly) << turn.dheading_deg << " deg: " << anomaly.value_or("");
      // The turn lasted as long as the boat turned: the stamps are the sentences' times.
      const double turned_s = std::abs(turn.dheading_deg) / 12.0;
      EXPECT_NEAR(raw.samples().back().t_s - raw.samples().front().t_s, turned_s, 0.45);
      if (!anomaly) ++completed;
    }
    EXPECT_EQ(completed, static_cast<int>(turns.size()));
  }
}

}  // namespace
