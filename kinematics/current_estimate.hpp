#pragma once
// A uniform current from steady legs (thesis §6.3).
//
// A vehicle with only GNSS and a compass sees its velocity over ground. On a steady leg (held
// course and speed, as the ConditionSet establishes before every turn) that velocity is the
// velocity through the water, along the heading, plus the current:
//
//   v_ground = w · (sin ψ, cos ψ) + c
//
// with ψ the heading (compass) and w the leg's speed through the water. w is not known: a speed
// loop that holds the measured speed (over ground) makes the vehicle faster through the water into
// the current than with it, so no single speed calibration fits every leg (a first version that
// assumed one found half the current). Only the component of v_ground across the heading is free
// of w, so each leg gives one equation, c · n = v_ground · n with n the heading's normal; legs on
// headings at least kMinHeadingSpreadDeg apart determine both components of c. Least squares
// (Eigen, QR); the covariance from the residuals. The speed through the water follows per leg.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/geometry.hpp"

namespace avk::kinematics {

inline constexpr double kMinHeadingSpreadDeg = 30.0;

// One steady leg of navigation (times increasing, positions in the local grid).
struct SteadyLeg {
  std::vector<double> t_s;
  std::vector<double> x_m;
  std::vector<double> y_m;
  double heading_deg = 0.0;      // the held heading (compass), clockwise from north
  double water_speed_mps = 0.0;  // the speed it was meant to make (commanded): for speed_scale
};

// The leg's velocity over ground: the slopes of least-squares lines through x(t) and y(t).
// Throws std::invalid_argument for fewer than 3 samples, unequal lengths or no time span.
std::array<double, 2> ground_velocity_mps(const SteadyLeg& leg);

struct CurrentEstimate {
  double east_mps = 0.0;
  double north_mps = 0.0;
  // The legs' mean ratio of speed through the water (along the heading, current removed) to the
  // speed they were taken to make.
  double speed_scale = 1.0;
  // Covariance of (east, north): [ee, en, nn] (m/s)^2.
  std::array<double, 3> covariance{};
  double residual_rms_mps = 0.0;
  std::size_t legs = 0;

  double speed_mps() const;
  double toward_deg() const;  // where the current sets, clockwise from north
  // The 1-sigma uncertainty of the speed and of the direction (deg), from the covariance.
  double speed_sd_mps() const;
  double toward_sd_deg() const;
};

struct CurrentEstimateResult {
  std::optional<CurrentEstimate> estimate;
  std::string why_not;  // when there is no estimate: too few legs, headings too alike
};

CurrentEstimateResult estimate_current(const std::vector<SteadyLeg>& legs);

// A turn over ground against its prediction through the water (the CKT's trajectory timed by its
// turns, placed at the turn's start): under a uniform current c their difference grows as c·t
// from the command (thesis §6.3: "compare actual trajectories to AVK predictions and use the
// differences to estimate external forces").
struct TurnResidual {
  std::vector<double> t_s;        // from the command
  std::vector<Point> residual_m;  // observed minus predicted, grid frame
};

// Each turn's c from least squares through the origin (r = c·t); the estimate is their mean and
// its covariance the turns' spread over their number: samples within a turn are far from
// independent (the prediction's error is smooth), turns are closer to it. `legs` counts the turns.
// Needs 2 turns with some time span; what the turns cannot tell apart from the current (a table
// that is wrong the same way on every heading) goes into it, which is why the steady legs are the
// primary estimate and this one its check.
CurrentEstimateResult estimate_current_from_turns(const std::vector<TurnResidual>& turns);

}  // namespace avk::kinematics
