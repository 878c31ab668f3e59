#pragma once
// Analytic turns for tests and benchmarks: a straight lead-in of length L followed by a
// constant-radius arc to the heading change, sampled in time at constant speed. The advance is
// L + R sin(dpsi) and the transfer R (1 - cos(dpsi)) (normalised frame).

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::testing {

struct ArcTurnSpec {
  double speed_mps = 1.0;
  double dheading_deg = 90.0;  // signed: + right
  double lead_in_m = 2.0;
  double radius_m = 3.0;
  double dt_s = 0.25;
  double tail_m = 0.0;       // straight run after the arc along the final heading
  kinematics::Pose start{};  // world pose of the first sample
  double position_noise_m = 0.0;
  double heading_noise_deg = 0.0;
  unsigned seed = 1;
  std::string vehicle_id = "test";
  std::string mission_id = "m1";
};

// Normalised right turn without lead-in: centre (R, 0), starting at the origin heading north,
// sampled every step_m of arc length.
inline kinematics::Polyline circular_arc(double radius_m, double dheading_deg, double step_m) {
  const double total = radius_m * kinematics::deg_to_rad(dheading_deg);
  kinematics::Polyline out;
  const auto n = static_cast<int>(std::ceil(total / step_m));
  for (int k = 0; k <= n; ++k) {
    const double a = std::min(total, k * step_m) / radius_m;
    out.push_back({radius_m * (1.0 - std::cos(a)), radius_m * std::sin(a)});
  }
  return out;
}

// Point at arc length s along the analytic normalised right turn, and its heading change (deg).
inline kinematics::Point arc_turn_point(const ArcTurnSpec& spec, double s, double* heading_deg) {
  const double dpsi = kinematics::deg_to_rad(std::abs(spec.dheading_deg));
  const double arc = spec.radius_m * dpsi;
  const double R = spec.radius_m;
  if (s <= spec.lead_in_m) {
    if (heading_deg) *heading_deg = 0.0;
    return {0.0, s};
  }
  if (s <= spec.lead_in_m + arc) {
    const double a = (s - spec.lead_in_m) / R;
    if (heading_deg) *heading_deg = kinematics::rad_to_deg(a);
    return {R * (1.0 - std::cos(a)), spec.lead_in_m + R * std::sin(a)};
  }
  const double rest = s - spec.lead_in_m - arc;
  if (heading_deg) *heading_deg = kinematics::rad_to_deg(dpsi);
  return {R * (1.0 - std::cos(dpsi)) + rest * std::sin(dpsi),
          spec.lead_in_m + R * std::sin(dpsi) + rest * std::cos(dpsi)};
}

inline double arc_turn_length_m(const ArcTurnSpec& spec) {
  return spec.lead_in_m + spec.radius_m * kinematics::deg_to_rad(std::abs(spec.dheading_deg)) +
         spec.tail_m;
}

// The turn as a TurnSequence in world coordinates (placed at spec.start, left when dheading < 0).
inline kinematics::TurnSequence make_arc_turn(const ArcTurnSpec& spec) {
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> pos(0.0,
                                       spec.position_noise_m > 0 ? spec.position_noise_m : 1.0);
  std::normal_distribution<double> hdg(0.0,
                                       spec.heading_noise_deg > 0 ? spec.heading_noise_deg : 1.0);
  const double total = arc_turn_length_m(spec);
  const auto side = kinematics::side_of(spec.dheading_deg);
  const double mirror = side == kinematics::TurnSide::left ? -1.0 : 1.0;
  kinematics::TurnMeta meta;
  meta.vehicle_id = spec.vehicle_id;
  meta.mission_id = spec.mission_id;
  meta.commanded_speed_mps = spec.speed_mps;
  meta.goal_dheading_deg = spec.dheading_deg;
  std::vector<kinematics::TurnSample> samples;
  const double step = spec.speed_mps * spec.dt_s;
  const auto n = static_cast<int>(std::ceil(total / step));
  for (int k = 0; k <= n; ++k) {
    const double s = std::min(total, k * step);
    double h = 0.0;
    const kinematics::Point p = arc_turn_point(spec, s, &h);
    kinematics::Point w = kinematics::place_normalized({p}, spec.start, side).front();
    double heading = spec.start.heading_deg + mirror * h;
    if (spec.position_noise_m > 0 && k > 0) {
      w.x_m += pos(rng);
      w.y_m += pos(rng);
    }
    if (spec.heading_noise_deg > 0 && k > 0) heading += hdg(rng);
    samples.push_back(
        {k * spec.dt_s, w.x_m, w.y_m, kinematics::wrap360_deg(heading), spec.speed_mps});
  }
  kinematics::TurnSequence turn(meta, samples);
  turn.fill_derived_metadata();
  turn.meta().initial_heading_deg = spec.start.heading_deg;
  return turn;
}

// The thesis' Figure 4-1 grid (10..160 deg x 0.5, 1.0, 1.5 m/s), `per_cell` turns a cell with
// alternating sides, from scattered start poses, for a vehicle whose lead-in (0.5 + u m) and
// radius (1 + 2u m) grow with speed.
inline std::vector<kinematics::TurnSequence> thesis_grid_turns(int per_cell, double dt_s,
                                                               double position_noise_m,
                                                               double heading_noise_deg = 0.0) {
  std::vector<kinematics::TurnSequence> turns;
  unsigned seed = 1;
  for (double u : {0.5, 1.0, 1.5}) {
    for (double d : {10.0, 40.0, 70.0, 100.0, 130.0, 160.0}) {
      for (int r = 0; r < per_cell; ++r) {
        ArcTurnSpec s;
        s.speed_mps = u;
        s.dheading_deg = r % 2 ? -d : d;
        s.lead_in_m = 0.5 + u;
        s.radius_m = 1.0 + 2.0 * u;
        s.dt_s = dt_s;
        s.position_noise_m = position_noise_m;
        s.heading_noise_deg = heading_noise_deg;
        s.seed = seed;
        s.start = {-40.0 + 7.0 * (seed % 11), 25.0 - 5.0 * (seed % 9), 31.0 * seed};
        s.vehicle_id = "synthetic";
        s.mission_id = "example";
        ++seed;
        turns.push_back(make_arc_turn(s));
      }
    }
  }
  return turns;
}

}  // namespace avk::testing
