#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/turn_measures.hpp"
#include "sim/sim_vehicle.hpp"
#include "sim/turn_scenario.hpp"
#include "sim/variability.hpp"

using namespace avk::sim;
namespace kin = avk::kinematics;

namespace {

// Time after the command at which the recorded heading first reaches `deg` of change.
double time_to_change(const TurnScenarioResult& r, double start_heading, double deg) {
  for (const auto& row : r.rows) {
    if (row.t_s < r.command_time_s) continue;
    if (kin::angle180_deg(row.heading_deg - start_heading) >= deg)
      return row.t_s - r.command_time_s;
  }
  return -1.0;
}

}  // namespace

// Thesis simulation setup (turn_rate 30, pMarinePID defaults, everything at 4 Hz) through the
// real SimVehicle + scheduler: the MOOS-IvP reference turn.
TEST(SimVehicle, UsimReproducesTheMoosReferenceTurn) {
  TurnScenarioConfig c;
  c.speed_mps = 1.0;
  c.dheading_deg = 90.0;
  c.min_settle_s = 60.0;
  c.after_turn_s = 30.0;
  c.completion.threshold_deg = 0.5;
  const TurnScenarioResult r = run_turn_scenario(c);
  ASSERT_TRUE(r.completed);
  double start_heading = 0.0;
  double min_speed = 10.0, max_after = 0.0;
  for (const auto& row : r.rows) {
    if (row.t_s <= r.command_time_s) start_heading = row.heading_deg;
    if (row.t_s > r.command_time_s) {
      min_speed = std::min(min_speed, row.speed_mps);
      if (kin::angle180_deg(row.heading_deg - start_heading) > 80.0) {
        max_after = std::max(max_after, row.speed_mps);
      }
    }
  }
  const double t45 = time_to_change(r, start_heading, 45.0);
  const double t80 = time_to_change(r, start_heading, 80.0);
  RecordProperty("t45_s", std::to_string(t45));
  RecordProperty("t80_s", std::to_string(t80));
  RecordProperty("min_speed_mps", std::to_string(min_speed));
  RecordProperty("max_speed_after_mps", std::to_string(max_after));
  std::cout << "reference turn: 45 deg after " << t45 << " s, 80 deg after " << t80
            << " s, speed sags to " << min_speed << " m/s, overshoots to " << max_after << " m/s\n";
  EXPECT_NEAR(t45, 7.9, 1.0);
  EXPECT_NEAR(t80, 17.4, 1.0);
  EXPECT_NEAR(min_speed, 0.70, 0.05);
}

TEST(SimVehicle, SameSeedSameTrajectoryBitForBit) {
  auto run = [](std::uint64_t seed) {
    TurnScenarioConfig c;
    c.vehicle = sim_vehicle_defaults("catamaran:m200");
    c.vehicle.environment.current.speed_mps = 0.2;
    c.vehicle.environment.current.toward_deg = 45.0;
    c.vehicle.environment.wind.mean_speed_mps = 4.0;
    c.vehicle.environment.wind.gust_sigma_mps = 1.0;
    c.scheduler = {seed, 0.1, true};
    c.speed_mps = 1.0;
    c.dheading_deg = -70.0;
    c.completion.threshold_deg = 5.0;
    return run_turn_scenario(c);
  };
  const auto a = run(3), b = run(3), c = run(4);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].x_m, b.rows[i].x_m);
    EXPECT_EQ(a.rows[i].heading_deg, b.rows[i].heading_deg);
    EXPECT_EQ(a.rows[i].t_s, b.rows[i].t_s);
  }
  bool differs = a.rows.size() != c.rows.size();
  for (std::size_t i = 0; !differs && i < a.rows.size(); ++i)
    differs = a.rows[i].x_m != c.rows[i].x_m;
  EXPECT_TRUE(differs);
  EXPECT_TRUE(a.completed);
}

TEST(SimVehicle, LeftAndRightTurnsMirrorOnUsim) {
  auto run = [](double d) {
    TurnScenarioConfig c;
    c.dheading_deg = d;
    return run_turn_scenario(c);
  };
  const auto r = run(60.0), l = run(-60.0);
  ASSERT_EQ(r.rows.size(), l.rows.size());
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    EXPECT_NEAR(r.rows[i].x_m, -l.rows[i].x_m, 1e-9);
    EXPECT_NEAR(r.rows[i].y_m, l.rows[i].y_m, 1e-9);
  }
}

TEST(SimVehicle, CatamaranCompletesTurnsBothWaysAtSeveralSpeeds) {
  for (const char* kind : {"catamaran:m200", "catamaran:heron", "catamaran:otter"}) {
    for (double u : {0.5, 1.0, 1.5}) {
      TurnScenarioConfig c;
      c.vehicle = sim_vehicle_defaults(kind);
      c.speed_mps = u;
      c.dheading_deg = u == 1.0 ? -100.0 : 100.0;
      c.completion.threshold_deg = 5.0;
      const auto r = run_turn_scenario(c);
      EXPECT_TRUE(r.completed) << kind << " " << u;
      const auto at = kin::advance_transfer(r.turn);
      EXPECT_GT(at.advance_m, 0.0) << kind << " " << u;
      EXPECT_GT(at.transfer_m, 0.0) << kind << " " << u;
    }
  }
}

TEST(SimVehicle, NavOutageMakesTheLinkStale) {
  Scheduler s;
  SimVehicle v(sim_vehicle_defaults("usim"), s);
  s.add("helm", 4.0, [&](double now) { v.command({now, 0.0, 1.0}); });
  s.run_until(5.0);
  EXPECT_EQ(v.link_state(5.0), avk::vehicle::LinkState::live);
  v.set_nav_outage(true);
  s.run_until(7.5);
  EXPECT_EQ(v.link_state(7.5), avk::vehicle::LinkState::stale);
  v.set_nav_outage(false);
  s.run_until(8.0);
  EXPECT_EQ(v.link_state(8.0), avk::vehicle::LinkState::live);
}

TEST(SimVehicle, AllStopStopsTheVehicleUntilTheNextCommand) {
  Scheduler s;
  SimVehicle v(sim_vehicle_defaults("usim"), s);
  bool stop = false;
  s.add("helm", 4.0, [&](double now) {
    if (stop) {
      v.all_stop(now);
    } else {
      v.command({now, 0.0, 1.0});
    }
  });
  s.run_until(60.0);
  EXPECT_NEAR(v.truth().speed_over_ground_mps, 1.0, 0.05);
  stop = true;
  s.run_until(70.0);
  // uSimMarine halves its speed towards the target each step: zero only in the limit.
  EXPECT_LT(v.truth().speed_over_ground_mps, 1e-6);
  EXPECT_EQ(v.last_actuators()->thrust_pct, 0.0);
}

TEST(SimVehicle, TakeNavHandsOverEverySampleOnce) {
  Scheduler s;
  SimVehicleConfig c = sim_vehicle_defaults("catamaran:m200");
  SimVehicle v(c, s);
  std::size_t n = 0;
  double last_t = -1.0;
  s.add("helm", 3.0, [&](double now) {
    for (const auto& nav : v.take_nav()) {
      EXPECT_GT(nav.t_s, last_t);
      last_t = nav.t_s;
      ++n;
    }
    v.command({now, 0.0, 1.0});
  });
  s.run_until(10.0);
  EXPECT_GE(n, 99u);  // 10 Hz for 10 s, minus what arrives after the helm's last tick
  EXPECT_LE(n, 101u);
}

// The M200 runs the thesis' in-water controller (Table 3.1), the other hulls the simulation one
// (Table 5.1); "catamaran" alone is the M200.
TEST(SimVehicle, KindDefaultsNameTheirPlantAndController) {
  const auto table31 = avk::vehicle::MarinePidConfig::m200_in_water();
  const auto table51 = avk::vehicle::MarinePidConfig::thesis_sim();
  for (const char* kind : {"catamaran", "catamaran:m200"}) {
    const SimVehicleConfig c = sim_vehicle_defaults(kind);
    EXPECT_EQ(c.kind, avk::vehicle::VehicleKind::catamaran_m200);
    ASSERT_TRUE(c.catamaran);
    EXPECT_EQ(c.catamaran->thruster, ThrusterKind::waterjet);
    EXPECT_EQ(c.pid.yaw.kp, table31.yaw.kp);
    EXPECT_EQ(c.pid.yaw.ki, table31.yaw.ki);
    EXPECT_EQ(c.pid.yaw.integral_limit, table31.yaw.integral_limit);
    EXPECT_EQ(c.controller_hz, 4.0);  // pMarinePID AppTick
    EXPECT_EQ(c.plant_hz, 10.0);      // iM200 AppTick: navigation at 10 Hz
  }
  for (const char* kind : {"catamaran:heron", "catamaran:otter", "usim"}) {
    const SimVehicleConfig c = sim_vehicle_defaults(kind);
    EXPECT_STREQ(avk::vehicle::to_string(c.kind), kind);
    EXPECT_EQ(c.pid.yaw.kp, table51.yaw.kp) << kind;
    EXPECT_EQ(c.pid.yaw.ki, table51.yaw.ki) << kind;
  }
  EXPECT_EQ(sim_vehicle_defaults("catamaran:heron").catamaran->thruster, ThrusterKind::thrust);
}

TEST(SimVehicle, UnknownKindIsNamed) {
  try {
    sim_vehicle_defaults("submarine");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("submarine"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("catamaran:heron"), std::string::npos);
  }
  EXPECT_THROW(sim_vehicle_defaults("catamaran:ferry"), std::invalid_argument);
}

TEST(Variability, JitterMakesAFewDistinctOutcomesAndNoJitterNone) {
  VariabilityConfig vc;
  vc.repeats = 12;
  vc.base.completion.threshold_deg = 2.0;
  vc.jitter = false;
  const auto steady = run_variability(vc);
  EXPECT_EQ(steady.distinct_outcomes, 1);
  EXPECT_NEAR(steady.advance_m.sd, 0.0, 1e-12);
  vc.jitter = true;
  const auto jittered = run_variability(vc);
  EXPECT_GT(jittered.distinct_outcomes, 1);
  EXPECT_GT(jittered.advance_cv, 0.0);
  EXPECT_LT(jittered.advance_cv, 0.2);
}
