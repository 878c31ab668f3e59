#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "kinematics/angles.hpp"
#include "sim/catamaran.hpp"

using namespace avk::sim;
using avk::kinematics::angle180_deg;
using avk::kinematics::deg_to_rad;

namespace {

const std::vector<CatamaranParams>& vehicles() {
  static const std::vector<CatamaranParams> v = {CatamaranParams::m200(), CatamaranParams::heron(),
                                                 CatamaranParams::otter()};
  return v;
}

void run(CatamaranPlant& p, double duration_s, double left_pct, double right_pct,
         double dt_s = 0.1) {
  const int n = static_cast<int>(std::lround(duration_s / dt_s));
  for (int i = 0; i < n; ++i)
    p.advance(dt_s, left_pct, right_pct);
}

// (east, north) velocity over ground from the body velocity.
Eigen::Vector2d ground_velocity_en(const CatamaranState& s) {
  const double psi = deg_to_rad(s.heading_deg);
  return {s.u_mps * std::sin(psi) + s.v_mps * std::cos(psi),
          s.u_mps * std::cos(psi) - s.v_mps * std::sin(psi)};
}

// Root of X_u u + X_uu |u|u + 2 T = 0, solved here rather than with the plant's own helper.
double balance_speed_mps(const CatamaranParams& p, double thrust_each_n) {
  const double t = 2.0 * thrust_each_n;
  const double a = -p.xuu, b = -p.xu;
  if (a == 0.0) return t / b;
  const double mag = (-b + std::sqrt(b * b + 4.0 * a * std::abs(t))) / (2.0 * a);
  return t >= 0.0 ? mag : -mag;
}

EnvironmentConfig gusty(std::uint64_t seed) {
  EnvironmentConfig c;
  c.current = {0.3, 60.0};
  c.wind.mean_speed_mps = 6.0;
  c.wind.from_deg = 250.0;
  c.wind.gust_sigma_mps = 2.0;
  c.wind.gust_time_constant_s = 3.0;
  c.seed = seed;
  return c;
}

void expect_states_near(const CatamaranState& a, const CatamaranState& b, double tol) {
  EXPECT_NEAR(a.x_m, b.x_m, tol);
  EXPECT_NEAR(a.y_m, b.y_m, tol);
  EXPECT_NEAR(angle180_deg(a.heading_deg - b.heading_deg), 0.0, tol);
  EXPECT_NEAR(a.u_mps, b.u_mps, tol);
  EXPECT_NEAR(a.v_mps, b.v_mps, tol);
  EXPECT_NEAR(a.r_rps, b.r_rps, tol);
  EXPECT_NEAR(a.left_actuator, b.left_actuator, tol);
  EXPECT_NEAR(a.right_actuator, b.right_actuator, tol);
}

}  // namespace

TEST(Catamaran, ParameterSetsAndThrustMaps) {
  ASSERT_TRUE(CatamaranParams::by_name("m200"));
  ASSERT_TRUE(CatamaranParams::by_name("heron"));
  ASSERT_TRUE(CatamaranParams::by_name("otter"));
  EXPECT_FALSE(CatamaranParams::by_name("ferry"));
  // The Heron is what "m200" was before the waterjets: its Gazebo numbers, linear thrust map.
  const CatamaranParams heron = *CatamaranParams::by_name("heron");
  EXPECT_EQ(heron.name, "heron");
  EXPECT_EQ(heron.thruster, ThrusterKind::thrust);
  EXPECT_DOUBLE_EQ(heron.max_speed_mps, 1.7);
  EXPECT_DOUBLE_EQ(heron.lag_s, 0.05);
  EXPECT_DOUBLE_EQ(heron.mass(2, 2), 12.0);
  EXPECT_EQ(heron.nr_per_speed, 0.0);
  EXPECT_DOUBLE_EQ(heron.thrust_n(100.0), 33.6);
  EXPECT_DOUBLE_EQ(heron.thrust_n(50.0), 16.8);
  EXPECT_DOUBLE_EQ(heron.thrust_n(-100.0), -19.88);
  EXPECT_DOUBLE_EQ(heron.thrust_n(-25.0), -4.97);
  EXPECT_DOUBLE_EQ(heron.thrust_n(150.0), 33.6);
  EXPECT_EQ(heron.thrust_n(0.0), 0.0);

  // The M200: waterjets on the Heron's hull, sized to its published 2 m/s top speed.
  const CatamaranParams m200 = *CatamaranParams::by_name("m200");
  EXPECT_EQ(m200.name, "m200");
  EXPECT_EQ(m200.thruster, ThrusterKind::waterjet);
  EXPECT_DOUBLE_EQ(m200.length_m, 1.35);
  EXPECT_DOUBLE_EQ(m200.beam_m, 0.98);
  EXPECT_NEAR(m200.mass(0, 0), 29.0 * 1.05, 1e-12);
  EXPECT_EQ(m200.xu, heron.xu);
  EXPECT_EQ(m200.xuu, heron.xuu);
  EXPECT_NEAR(m200.steady_surge_speed_mps(100.0), 2.0, 1e-12);
  EXPECT_NEAR(m200.max_speed_mps, 1.8, 1e-12);
  EXPECT_LT(m200.nr_per_speed, 0.0);

  const CatamaranParams otter = *CatamaranParams::by_name("otter");
  EXPECT_NEAR(otter.n_max_rps, 103.9, 0.05);
  EXPECT_NEAR(otter.n_min_rps, -101.7, 0.05);
  // Full ahead is half the Otter's 24.4 kgf per propeller; thrust goes as n|n|.
  EXPECT_NEAR(otter.thrust_n(100.0), 0.5 * 24.4 * 9.81, 1e-9);
  EXPECT_NEAR(otter.thrust_n(50.0), 0.25 * otter.thrust_n(100.0), 1e-9);
  EXPECT_NEAR(otter.thrust_n(-100.0), -0.5 * 13.6 * 9.81, 1e-9);
  // 6 kn design speed at full thrust, operated at 90 % of it.
  EXPECT_NEAR(otter.steady_surge_speed_mps(100.0), 3.087, 0.001);
  EXPECT_NEAR(otter.max_speed_mps, 0.9 * otter.steady_surge_speed_mps(100.0), 1e-12);
}

TEST(Catamaran, ZeroThrustFromRestStaysAtRest) {
  for (const auto& params : vehicles()) {
    CatamaranPlant p(params, EnvironmentConfig{}, CatamaranState{3.0, -4.0, 123.0});
    run(p, 60.0, 0.0, 0.0, 0.25);
    EXPECT_EQ(p.state().x_m, 3.0) << params.name;
    EXPECT_EQ(p.state().y_m, -4.0) << params.name;
    EXPECT_NEAR(p.state().heading_deg, 123.0, 1e-12) << params.name;
    EXPECT_EQ(p.state().u_mps, 0.0) << params.name;
    EXPECT_EQ(p.state().v_mps, 0.0) << params.name;
    EXPECT_EQ(p.state().r_rps, 0.0) << params.name;
    EXPECT_EQ(p.speed_over_ground_mps(), 0.0) << params.name;
    EXPECT_NEAR(p.time_s(), 60.0, 1e-12) << params.name;
  }
}

TEST(Catamaran, MovingWithTheWaterDriftsAtTheCurrentExactly) {
  EnvironmentConfig env;
  env.current = {0.5, 60.0};
  const Eigen::Vector2d current(0.5 * std::sin(deg_to_rad(60.0)), 0.5 * std::cos(deg_to_rad(60.0)));
  for (const auto& params : vehicles()) {
    // At rest in the water: body velocity over ground is the current's, seen from heading 10.
    const double psi = deg_to_rad(10.0);
    CatamaranState s0;
    s0.heading_deg = 10.0;
    s0.u_mps = current.y() * std::cos(psi) + current.x() * std::sin(psi);
    s0.v_mps = -current.y() * std::sin(psi) + current.x() * std::cos(psi);
    CatamaranPlant p(params, env, s0);
    run(p, 20.0, 0.0, 0.0);
    EXPECT_NEAR(p.state().heading_deg, 10.0, 1e-12) << params.name;
    EXPECT_NEAR(p.state().r_rps, 0.0, 1e-12) << params.name;
    EXPECT_NEAR(p.water_relative_velocity().norm(), 0.0, 1e-12) << params.name;
    EXPECT_NEAR(p.state().x_m, 20.0 * current.x(), 1e-9) << params.name;
    EXPECT_NEAR(p.state().y_m, 20.0 * current.y(), 1e-9) << params.name;
    EXPECT_NEAR(p.course_over_ground_deg(), 60.0, 1e-9) << params.name;
    EXPECT_NEAR(p.speed_over_ground_mps(), 0.5, 1e-12) << params.name;
  }
}

TEST(Catamaran, PureCurrentCarriesAVehicleFromRest) {
  for (double toward_deg : {0.0, 90.0, 200.0, 60.0}) {
    EnvironmentConfig env;
    env.current = {0.5, toward_deg};
    const Eigen::Vector2d current(0.5 * std::sin(deg_to_rad(toward_deg)),
                                  0.5 * std::cos(deg_to_rad(toward_deg)));
    for (const auto& params : vehicles()) {
      // At rest over ground, so the water first streams past the hull.
      CatamaranPlant p(params, env);
      run(p, 120.0, 0.0, 0.0);
      const Eigen::Vector2d v0 = ground_velocity_en(p.state());
      const double x0 = p.state().x_m, y0 = p.state().y_m;
      run(p, 10.0, 0.0, 0.0);
      const Eigen::Vector2d v = ground_velocity_en(p.state());
      EXPECT_NEAR(v.x(), current.x(), 1e-3) << params.name << " " << toward_deg;
      EXPECT_NEAR(v.y(), current.y(), 1e-3) << params.name << " " << toward_deg;
      EXPECT_NEAR(v0.x(), current.x(), 1e-3) << params.name << " " << toward_deg;
      EXPECT_NEAR(v0.y(), current.y(), 1e-3) << params.name << " " << toward_deg;
      EXPECT_NEAR((p.state().x_m - x0) / 10.0, current.x(), 1e-3) << params.name;
      EXPECT_NEAR((p.state().y_m - y0) / 10.0, current.y(), 1e-3) << params.name;
      EXPECT_NEAR(p.state().r_rps, 0.0, 1e-6) << params.name << " " << toward_deg;
      // Water along or across a hull with no sway–yaw coupling turns nothing; obliquely, the
      // Munk moment may turn the hull while the water slows past it, but not after. "Nothing"
      // up to rounding: the cross-flow strips' moments cancel to ~1e-18 N·m, not exactly.
      if (params.mass(1, 2) == 0.0 && std::fmod(toward_deg, 90.0) == 0.0) {
        EXPECT_NEAR(angle180_deg(p.state().heading_deg), 0.0, 1e-12)
            << params.name << " " << toward_deg;
      }
    }
  }
}

TEST(Catamaran, SteadySpeedMatchesThrustDampingBalance) {
  for (const auto& params : vehicles()) {
    for (double pct : {25.0, 50.0, 80.0, 100.0, -60.0}) {
      CatamaranPlant p(params, EnvironmentConfig{});
      run(p, 60.0, pct, pct);
      const double expected = balance_speed_mps(params, params.thrust_n(pct));
      EXPECT_NEAR(p.state().u_mps, expected, 1e-3 * std::abs(expected))
          << params.name << " " << pct;
      EXPECT_NEAR(params.steady_surge_speed_mps(pct), expected, 1e-12 * std::abs(expected));
      EXPECT_EQ(p.state().v_mps, 0.0);
      EXPECT_EQ(p.state().heading_deg, 0.0);
      EXPECT_EQ(p.state().x_m, 0.0);
    }
  }
}

TEST(Catamaran, SwappedThrustMirrorsTheTurn) {
  for (const auto& params : vehicles()) {
    for (double heading0 : {0.0, 37.0}) {
      CatamaranState s0;
      s0.heading_deg = heading0;
      s0.u_mps = 0.4;
      CatamaranPlant a(params, EnvironmentConfig{}, s0);
      CatamaranPlant b(params, EnvironmentConfig{}, s0);
      for (int i = 0; i < 300; ++i) {
        const double left = 70.0 + 30.0 * std::sin(0.05 * i), right = 20.0 - 0.2 * i;
        a.advance(0.1, left, right);
        b.advance(0.1, right, left);
      }
      // Mirror b across the initial course line through the start point.
      const Eigen::Vector2d d(std::sin(deg_to_rad(heading0)), std::cos(deg_to_rad(heading0)));
      const Eigen::Vector2d pb(b.state().x_m, b.state().y_m);
      const Eigen::Vector2d mirrored = 2.0 * pb.dot(d) * d - pb;
      const double tol = heading0 == 0.0 ? 1e-12 : 1e-9;
      EXPECT_NEAR(a.state().x_m, mirrored.x(), tol) << params.name;
      EXPECT_NEAR(a.state().y_m, mirrored.y(), tol) << params.name;
      EXPECT_NEAR(angle180_deg(a.state().heading_deg - heading0),
                  -angle180_deg(b.state().heading_deg - heading0), tol)
          << params.name;
      EXPECT_NEAR(a.state().u_mps, b.state().u_mps, tol);
      EXPECT_NEAR(a.state().v_mps, -b.state().v_mps, tol);
      EXPECT_NEAR(a.state().r_rps, -b.state().r_rps, tol);
      // And the turn is a real one.
      EXPECT_GT(std::abs(angle180_deg(a.state().heading_deg - heading0)), 10.0) << params.name;
      EXPECT_GT((Eigen::Vector2d(a.state().x_m, a.state().y_m) - pb).norm(), 1.0) << params.name;
    }
  }
}

TEST(Catamaran, LeftFasterTurnsToStarboard) {
  for (const auto& params : vehicles()) {
    CatamaranPlant p(params, EnvironmentConfig{});
    run(p, 2.0, 80.0, 20.0);
    EXPECT_GT(p.state().r_rps, 0.0) << params.name;
    EXPECT_GT(p.yaw_rate_dps(), 0.0) << params.name;
    EXPECT_GT(p.state().heading_deg, 5.0) << params.name;
    EXPECT_LT(p.state().heading_deg, 180.0) << params.name;
    EXPECT_GT(p.state().x_m, 0.0) << params.name;  // heading north, starboard is east
    EXPECT_GT(p.left_thrust_n(), p.right_thrust_n());
  }
}

TEST(Catamaran, HeadingWrapsBothWays) {
  for (const auto& params : vehicles()) {
    for (auto [start, left, right] : {std::tuple{350.0, 80.0, 20.0}, {10.0, 20.0, 80.0}}) {
      CatamaranState s0;
      s0.heading_deg = start;
      CatamaranPlant p(params, EnvironmentConfig{}, s0);
      double prev = start, turned = 0.0;
      for (int i = 0; i < 100; ++i) {
        p.advance(0.1, left, right);
        const double h = p.state().heading_deg;
        EXPECT_GE(h, 0.0);
        EXPECT_LT(h, 360.0);
        const double step = angle180_deg(h - prev);
        EXPECT_LT(std::abs(step), 30.0);
        turned += step;
        prev = h;
      }
      // Enough turn to have crossed north, in the right direction.
      EXPECT_GT(left > right ? turned : -turned, 30.0) << params.name;
      EXPECT_NEAR(angle180_deg(p.state().heading_deg - (start + turned)), 0.0, 1e-9);
    }
  }
}

TEST(Catamaran, FixedInternalStepMakesTheCallPatternIrrelevant) {
  for (const auto& params : vehicles()) {
    CatamaranPlant a(params, gusty(5)), b(params, gusty(5)), c(params, gusty(5));
    for (int i = 0; i < 1000; ++i)
      a.advance(0.01, 90.0, 40.0);
    for (int i = 0; i < 40; ++i)
      b.advance(0.25, 90.0, 40.0);
    for (int i = 0; i < 769; ++i)
      c.advance(0.013, 90.0, 40.0);
    c.advance(10.0 - 769 * 0.013, 90.0, 40.0);
    EXPECT_NEAR(a.time_s(), 10.0, 1e-12);
    EXPECT_NEAR(b.time_s(), 10.0, 1e-12);
    EXPECT_NEAR(c.time_s(), 10.0, 1e-12);
    expect_states_near(a.state(), b.state(), 1e-9);
    expect_states_near(a.state(), c.state(), 1e-9);
    EXPECT_GT(std::abs(a.state().heading_deg), 1.0);  // something happened
    // The gust moved once per internal step, as a lone environment would.
    Environment lone(gusty(5));
    for (int i = 0; i < 1000; ++i)
      lone.advance(params.internal_step_s);
    EXPECT_EQ(a.environment().gust_mps(), lone.gust_mps());
    EXPECT_EQ(c.environment().gust_mps(), lone.gust_mps());

    // Off the grid too: the reported state is carried over the remainder the same way.
    CatamaranPlant d(params, gusty(5)), e(params, gusty(5));
    d.advance(0.135, 90.0, 40.0);
    e.advance(0.1, 90.0, 40.0);
    e.advance(0.035, 90.0, 40.0);
    expect_states_near(d.state(), e.state(), 1e-12);
    EXPECT_NEAR(d.time_s(), 0.135, 1e-15);
  }
}

TEST(Catamaran, ThrusterLagReaches63PercentAfterTheLag) {
  for (const auto& params : vehicles()) {
    CatamaranPlant p(params, EnvironmentConfig{});
    p.advance(params.lag_s, 100.0, -100.0);
    // RK4's own error at h = lag/5 or lag/10 is a few 1e-6.
    const double f = 1.0 - std::exp(-1.0);
    EXPECT_NEAR(p.state().left_actuator / params.actuator_target(100.0), f, 1e-4) << params.name;
    EXPECT_NEAR(p.state().right_actuator / params.actuator_target(-100.0), f, 1e-4) << params.name;
    run(p, 20.0 * params.lag_s, 100.0, -100.0, 0.013);
    EXPECT_NEAR(p.left_thrust_n(), params.thrust_n(100.0), 1e-6) << params.name;
    EXPECT_NEAR(p.right_thrust_n(), params.thrust_n(-100.0), 1e-6) << params.name;
  }
}

TEST(Catamaran, ReportedStateIsAtTheRequestedTimeBetweenGridSteps) {
  for (const auto& params : vehicles()) {
    // 0.037 s is 3 grid steps and 0.007 s more; the lag's exact response says where we are.
    CatamaranPlant p(params, EnvironmentConfig{});
    p.advance(0.037, 100.0, 0.0);
    EXPECT_NEAR(p.state().left_actuator / params.actuator_target(100.0),
                1.0 - std::exp(-0.037 / params.lag_s), 1e-5)
        << params.name;
    EXPECT_NEAR(p.time_s(), 0.037, 1e-15);
    // The partial step is not kept: carrying on lands on the same grid as one call would.
    p.advance(0.963, 100.0, 0.0);
    CatamaranPlant q(params, EnvironmentConfig{});
    q.advance(1.0, 100.0, 0.0);
    EXPECT_EQ(p.state().left_actuator, q.state().left_actuator);
    EXPECT_EQ(p.state().x_m, q.state().x_m);
  }
}

// The initial acceleration, by finite difference over a tiny advance, against the Fossen
// equations evaluated here: M ν̇_r = τ − C(ν_r) ν_r − D(ν_r) ν_r (+ cross-flow), and for a
// constant current ν̇ = ν̇_r + [r v_c, −r u_c, 0].
TEST(Catamaran, InitialAccelerationMatchesTheFossenEquations) {
  for (const auto& params : vehicles()) {
    EnvironmentConfig env;
    env.current = {0.4, 130.0};
    CatamaranState s0;
    s0.heading_deg = 20.0;
    s0.u_mps = 1.2;
    s0.v_mps = 0.3;
    s0.r_rps = 0.4;
    s0.left_actuator = params.actuator_target(70.0);
    s0.right_actuator = params.actuator_target(30.0);

    const double psi = deg_to_rad(20.0);
    const double ce = 0.4 * std::sin(deg_to_rad(130.0)), cn = 0.4 * std::cos(deg_to_rad(130.0));
    const double uc = cn * std::cos(psi) + ce * std::sin(psi);
    const double vc = -cn * std::sin(psi) + ce * std::cos(psi);
    const double u = s0.u_mps - uc, v = s0.v_mps - vc, r = s0.r_rps;
    const Eigen::Matrix3d& m = params.mass;
    const double tl = params.thrust_n(70.0), tr = params.thrust_n(30.0);
    Eigen::Vector3d tau(tl + tr, 0.0, (tl - tr) * params.thruster_y_m);
    Eigen::Matrix3d c;
    c << 0.0, 0.0, -m(1, 1) * v - m(1, 2) * r,  //
        0.0, 0.0, m(0, 0) * u,                  //
        m(1, 1) * v + m(1, 2) * r, -m(0, 0) * u, 0.0;
    const Eigen::Vector3d damping(-(params.xu * u + params.xuu * std::abs(u) * u),
                                  -(params.yv * v + params.yvv * std::abs(v) * v),
                                  -((params.nr + params.nr_per_speed * std::abs(u)) *
                                        (1.0 + params.yaw_damping_rate_gain * std::abs(r)) * r +
                                    params.nrr * std::abs(r) * r));
    Eigen::Vector3d cross_flow = Eigen::Vector3d::Zero();
    if (params.cross_flow_drag) {
      const int n = params.cross_flow_strips;
      const double dx = params.length_m / n;
      for (int i = 0; i < n; ++i) {
        const double x = -params.length_m / 2.0 + (i + 0.5) * dx;
        const double f = -0.5 * params.water_density_kg_m3 * params.draught_m *
                         params.cross_flow_cd * std::abs(v + x * r) * (v + x * r) * dx;
        cross_flow += Eigen::Vector3d(0.0, f, x * f);
      }
    }
    const Eigen::Vector3d nu_dot =
        m.inverse() * (tau - c * Eigen::Vector3d(u, v, r) - damping + cross_flow) +
        Eigen::Vector3d(r * vc, -r * uc, 0.0);

    const double h = 1e-5;
    CatamaranPlant p(params, env, s0);
    p.advance(h, 70.0, 30.0);
    const Eigen::Vector3d fd((p.state().u_mps - s0.u_mps) / h, (p.state().v_mps - s0.v_mps) / h,
                             (p.state().r_rps - s0.r_rps) / h);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(fd(k), nu_dot(k), 1e-3 * (1.0 + std::abs(nu_dot(k)))) << params.name << " " << k;
    }
    // And the position moves with the velocity over ground.
    EXPECT_NEAR((p.state().x_m - s0.x_m) / h, s0.u_mps * std::sin(psi) + s0.v_mps * std::cos(psi),
                1e-3);
    EXPECT_NEAR((p.state().y_m - s0.y_m) / h, s0.u_mps * std::cos(psi) - s0.v_mps * std::sin(psi),
                1e-3);
  }
}

TEST(Catamaran, WindSeedDeterminesTheRun) {
  auto trajectory = [](std::uint64_t seed) {
    CatamaranPlant p(CatamaranParams::m200(), gusty(seed));
    std::vector<double> out;
    for (int i = 0; i < 300; ++i) {
      p.advance(0.1, 60.0, 50.0);
      out.insert(out.end(), {p.state().x_m, p.state().y_m, p.state().heading_deg});
    }
    return out;
  };
  const std::vector<double> a = trajectory(11);
  EXPECT_EQ(a, trajectory(11));  // bit-identical
  const std::vector<double> b = trajectory(12);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(std::abs(a.back() - b.back()) + std::abs(a[a.size() - 3] - b[b.size() - 3]), 1e-3);
}

TEST(Catamaran, WindPushesAStationaryVehicleDownwind) {
  for (const auto& params : vehicles()) {
    // Head wind from the north: straight back south, no turn.
    EnvironmentConfig head;
    head.wind.mean_speed_mps = 5.0;
    CatamaranPlant p(params, head);
    run(p, 60.0, 0.0, 0.0);
    EXPECT_LT(p.state().y_m, -1.0) << params.name;
    EXPECT_NEAR(p.state().x_m, 0.0, 1e-12) << params.name;
    EXPECT_NEAR(p.state().heading_deg, 0.0, 1e-12) << params.name;
    // Steady drift where hull damping balances the wind on a hull moving astern at u < 0:
    // X_u u + X_uu |u|u + q ((−V − u)|−V − u| + u|u|) = 0, by bisection.
    const WindConfig& w = head.wind;
    const double q =
        0.5 * w.air_density_kg_m3 * w.drag_coefficient_x * params.beam_m * w.windage_height_m;
    auto net = [&](double u) {
      const double ua = -5.0 - u;
      return params.xu * u + params.xuu * std::abs(u) * u +
             q * (std::abs(ua) * ua + std::abs(u) * u);
    };
    double lo = -5.0, hi = 0.0;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (net(mid) > 0.0 ? lo : hi) = mid;
    }
    EXPECT_NEAR(p.state().u_mps, 0.5 * (lo + hi), 1e-6) << params.name;

    // Beam wind from the east: pushed west.
    EnvironmentConfig beam;
    beam.wind.mean_speed_mps = 5.0;
    beam.wind.from_deg = 90.0;
    CatamaranPlant q2(params, beam);
    run(q2, 30.0, 0.0, 0.0);
    EXPECT_LT(q2.state().x_m, -1.0) << params.name;
    EXPECT_LT(std::abs(q2.state().y_m), std::abs(q2.state().x_m)) << params.name;
  }
}

TEST(Catamaran, RejectsInvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CatamaranPlant p(CatamaranParams::m200(), EnvironmentConfig{});
  EXPECT_THROW(p.advance(-0.1, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(p.advance(nan, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(p.advance(0.1, nan, 0.0), std::invalid_argument);
  CatamaranParams bad = CatamaranParams::m200();
  bad.lag_s = 0.0;
  EXPECT_THROW(CatamaranPlant(bad, EnvironmentConfig{}), std::invalid_argument);
  bad = CatamaranParams::m200();
  bad.xu = 1.0;
  EXPECT_THROW(CatamaranPlant(bad, EnvironmentConfig{}), std::invalid_argument);
  bad = CatamaranParams::m200();
  bad.mass(1, 1) = -1.0;
  EXPECT_THROW(CatamaranPlant(bad, EnvironmentConfig{}), std::invalid_argument);
  CatamaranState s;
  s.u_mps = nan;
  EXPECT_THROW(CatamaranPlant(CatamaranParams::otter(), EnvironmentConfig{}, s),
               std::invalid_argument);
  // Commands beyond ±100 % are clamped, not rejected.
  CatamaranPlant a(CatamaranParams::m200(), EnvironmentConfig{});
  CatamaranPlant b(CatamaranParams::m200(), EnvironmentConfig{});
  a.advance(1.0, 250.0, -300.0);
  b.advance(1.0, 100.0, -100.0);
  EXPECT_EQ(a.state().x_m, b.state().x_m);
  EXPECT_EQ(a.state().heading_deg, b.state().heading_deg);
}

// The figures the brief asks for, printed; the checks only keep them sane.
TEST(Catamaran, ReportSteadyFigures) {
  for (const auto& params : vehicles()) {
    CatamaranPlant p(params, EnvironmentConfig{});
    run(p, 60.0, 100.0, 100.0);
    std::printf("[figures] %s steady speed at 100 %%: %.3f m/s (max_speed_mps %.3f)\n",
                params.name.c_str(), p.state().u_mps, params.max_speed_mps);
    EXPECT_GT(p.state().u_mps, params.max_speed_mps);
  }
  for (const auto& params : {CatamaranParams::m200(), CatamaranParams::heron()}) {
    for (auto [left, right] : {std::pair{100.0, 0.0}, std::pair{60.0, 40.0}}) {
      CatamaranPlant p(params, EnvironmentConfig{});
      run(p, 120.0, left, right);
      const double r0 = p.state().r_rps;
      run(p, 10.0, left, right);
      const double r = p.state().r_rps, speed = p.speed_over_ground_mps();
      std::printf(
          "[figures] %s (%.0f %%, %.0f %%): yaw rate %.2f deg/s, speed %.3f m/s (u %.3f, v %.3f), "
          "turning radius %.2f m, diameter %.2f boat lengths\n",
          params.name.c_str(), left, right, p.yaw_rate_dps(), speed, p.state().u_mps,
          p.state().v_mps, speed / r, 2.0 * speed / r / p.params().length_m);
      EXPECT_NEAR(r, r0, 1e-9) << params.name;  // steady
      EXPECT_GT(r, 0.0) << params.name;
    }
  }
}

// The waterjet against analytic cases. Thrust goes as the impeller speed squared, and the speed
// lags the command as a first-order system: n(t) = n_target (1 − e^(−t/τ)) from rest.
TEST(CatamaranWaterjet, ThrustGoesAsTheImpellerSpeedSquared) {
  const CatamaranParams p = CatamaranParams::m200();
  const double full = p.max_forward_thrust_n;
  // 2 T = −X_u U − X_uu U² at the published 2 m/s.
  EXPECT_NEAR(full, 0.5 * (16.45 * 2.0 + 2.94 * 4.0), 1e-12);
  for (double pct : {10.0, 25.0, 50.0, 66.0, 100.0}) {
    const double f = pct / 100.0;
    EXPECT_NEAR(p.actuator_target(pct), f * p.n_max_rps, 1e-9) << pct;
    EXPECT_NEAR(p.thrust_n(pct), full * f * f, 1e-12) << pct;
  }
  EXPECT_DOUBLE_EQ(p.thrust_n(150.0), full);  // clamped at 100 %
  EXPECT_EQ(p.thrust_n(0.0), 0.0);
}

TEST(CatamaranWaterjet, ReverseIsTheBucketsFractionOfAheadThrust) {
  const CatamaranParams p = CatamaranParams::m200();
  EXPECT_GT(p.jet_reverse_fraction, 0.0);
  EXPECT_LT(p.jet_reverse_fraction, 1.0);
  for (double pct : {25.0, 50.0, 100.0}) {
    EXPECT_NEAR(p.thrust_n(-pct), -p.jet_reverse_fraction * p.thrust_n(pct), 1e-12) << pct;
  }
  // Full astern settles where the reversed jet balances the hull's drag going astern: much
  // slower than full ahead.
  CatamaranPlant plant(p, EnvironmentConfig{});
  run(plant, 60.0, -100.0, -100.0);
  const double astern = balance_speed_mps(p, -p.jet_reverse_fraction * p.max_forward_thrust_n);
  EXPECT_NEAR(plant.state().u_mps, astern, 1e-3 * std::abs(astern));
  EXPECT_NEAR(p.steady_surge_speed_mps(-100.0), astern, 1e-12);
  EXPECT_LT(std::abs(astern), 0.5 * p.steady_surge_speed_mps(100.0));
}

TEST(CatamaranWaterjet, ImpellerSpinUpIsAFirstOrderLag) {
  const CatamaranParams p = CatamaranParams::m200();
  CatamaranPlant plant(p, EnvironmentConfig{});
  double t = 0.0;
  for (double step : {0.05, 0.1, 0.15, 0.3, 0.6}) {
    plant.advance(step, 80.0, -40.0);
    t += step;
    const double g = 1.0 - std::exp(-t / p.lag_s);
    EXPECT_NEAR(plant.state().left_actuator, g * p.actuator_target(80.0), 1e-4 * p.n_max_rps) << t;
    EXPECT_NEAR(plant.state().right_actuator, g * p.actuator_target(-40.0), 1e-4 * p.n_max_rps)
        << t;
    // Thrust follows the square of the lagged impeller speed, not the lag of the thrust.
    EXPECT_NEAR(plant.left_thrust_n(), p.max_forward_thrust_n * std::pow(0.8 * g, 2), 1e-3) << t;
    EXPECT_NEAR(plant.right_thrust_n(),
                -p.jet_reverse_fraction * p.max_forward_thrust_n * std::pow(0.4 * g, 2), 1e-3)
        << t;
  }
}

TEST(CatamaranWaterjet, SteadyStraightSpeedFromThrustAndDrag) {
  const CatamaranParams p = CatamaranParams::m200();
  for (double pct : {30.0, 66.0, 100.0}) {
    CatamaranPlant plant(p, EnvironmentConfig{});
    run(plant, 60.0, pct, pct);
    const double f = pct / 100.0;
    const double expected = balance_speed_mps(p, p.max_forward_thrust_n * f * f);
    EXPECT_NEAR(plant.state().u_mps, expected, 1e-3 * expected) << pct;
    EXPECT_NEAR(p.steady_surge_speed_mps(pct), expected, 1e-12) << pct;
  }
}

// The hull-lift yaw damping grows with speed, so a yaw rate decays faster the faster the hull
// moves; at rest the M200 damps yaw as the Heron's hull does.
TEST(CatamaranWaterjet, YawDampingGrowsWithSpeed) {
  const CatamaranParams p = CatamaranParams::m200();
  auto decay = [&](double u) {
    CatamaranState s;
    s.u_mps = u;
    s.r_rps = 0.2;
    CatamaranPlant plant(p, EnvironmentConfig{}, s);
    plant.advance(1e-4, 0.0, 0.0);
    return (plant.state().r_rps - 0.2) / 1e-4;
  };
  EXPECT_LT(decay(1.5), decay(1.0));
  EXPECT_LT(decay(1.0), decay(0.0));
  EXPECT_LT(decay(0.0), 0.0);
}
