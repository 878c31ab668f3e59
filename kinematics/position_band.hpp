#pragma once
// Where the vehicle will be at each time of a prediction: a 2-D normal band about the predicted
// point at that time, not only a lateral corridor about the path.
//
// Four independent sources, added as covariances:
// - the navigation's position noise, constant: the prediction starts from a measured position;
// - the spread of the recorded turns about their mean at equal time, along the path (timing)
//   and across it (PredictedManeuver::along_sd_m, cross_sd_m), held past the turn's end: a turn
//   that came out late stays late;
// - the straight-leg scatter after the turn: each realisation of a steady leg makes good a
//   slightly different velocity (gusts, leeway, the speed loop's error), so the position error
//   grows linearly with the time since the turn ended, along and across the track;
// - the current estimate's uncertainty: a velocity error of covariance C carries the whole
//   prediction, so it adds C·t² from the command on.
//
// Frames: the local grid, metres; a covariance is [xx, xy, yy] in m².

#include <array>
#include <cstddef>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/timed_path.hpp"

namespace avk::kinematics {

using Covariance2 = std::array<double, 3>;  // [xx, xy, yy]

// 1-sigma growth rates of a straight-line prediction's error, per second since the turn ended.
struct MotionScatter {
  double along_mps = 0.0;
  double cross_mps = 0.0;
};

struct BandSources {
  MotionScatter scatter;
  // The navigation's position noise (1 sigma, each axis): the prediction is anchored on a
  // measured position, so the band never narrows below it, even at the command.
  double position_sd_m = 0.0;
  Covariance2 current_covariance_m2ps2{};  // of the current estimate, (m/s)²; zero: none
};

// One covariance per point of a placed (world frame) path. along_sd_m and cross_sd_m, when not
// empty, hold one value per path point (the turn's spread); growth starts at the time of point
// turn_points − 1 (clamped to the path). The along direction at a point is that of the segment
// arriving at it (leaving it, for the first point). Throws std::invalid_argument for spreads of
// the wrong size or an empty path.
std::vector<Covariance2> position_band(const TimedPath& path, const std::vector<double>& along_sd_m,
                                       const std::vector<double>& cross_sd_m,
                                       std::size_t turn_points, const BandSources& sources);

// The factor k with P(|z| <= k) = share for a 2-D standard normal z: sqrt(−2 ln(1 − share)).
// A point is inside the band of that share when its Mahalanobis distance is at most k. Throws
// std::invalid_argument for a share outside (0, 1).
double band_radius_factor(double share);

// d' C⁻¹ d, with a floor on the determinant so a degenerate band (a straight path without
// spread) counts a point on it as inside and one off it as far outside.
double mahalanobis2(const Covariance2& c, Point d);

// The band's ellipse at a share: semi-axes (m) and the major axis' direction (deg clockwise from
// north, in [0, 180)).
struct BandEllipse {
  double major_m = 0.0;
  double minor_m = 0.0;
  double major_axis_deg = 0.0;
};
BandEllipse band_ellipse(const Covariance2& c, double share);

// The variance of c along the unit direction n.
double variance_along(const Covariance2& c, Point n);

}  // namespace avk::kinematics
