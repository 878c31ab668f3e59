#pragma once
// Curve fits of a turn trajectory (thesis §3.3.2): only the geometric shape of a turn is kept, so
// the recorded points are replaced by a smooth curve. Two representations:
//  - poly4_xy: the thesis fit, y = f(x) with a quartic f. It cannot follow the straight lead-in of
//    a normalised turn (x stays ~0 while y grows) nor any turn past 90 degrees where x folds back,
//    so it is kept for comparison with the thesis and for files written with it.
//  - arc_length_spline: x(s), y(s) as a clamped cubic B-spline in (approximately) arc length s,
//    which follows lead-ins and turns up to 180 degrees and beyond.

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "kinematics/geometry.hpp"

namespace avk::kinematics {

enum class FitKind { poly4_xy, arc_length_spline };
const char* to_string(FitKind kind);
std::optional<FitKind> fit_kind_from_string(std::string_view name);

inline constexpr std::size_t kPoly4CoefficientCount = 5;
inline constexpr std::size_t kSplineDegree = 3;

struct CurveFit {
  FitKind kind = FitKind::arc_length_spline;
  // poly4_xy (the thesis fit): y = sum_k coefficients[k] * ((x - center) / scale)^k, k = 0..4,
  //   valid for x in [domain_min, domain_max]. Scaling x keeps the Vandermonde system well
  //   conditioned whatever the turn size.
  // arc_length_spline: clamped cubic B-spline x(s), y(s) with parameter s in
  //   [domain_min = 0, domain_max = arc length of the curve]; `knots` is the full knot vector
  //   (control_points.size() + 4 entries), `control_points` the (x,y) control points. s equals
  //   the arc length at both ends and is within a few percent of it in between.
  std::vector<double> coefficients;
  double center = 0.0, scale = 1.0, domain_min = 0.0, domain_max = 0.0;
  std::vector<double> knots;
  Polyline control_points;

  // Parameters outside [domain_min, domain_max] are clamped to it: neither representation means
  // anything beyond the data it was fitted to.
  Point evaluate(double parameter) const;  // x for poly4, s for spline
  // Tangent heading in deg clockwise from north, in [-90, 270) so that a normalised right turn
  // (0 at the start, up to 180 at the end) never wraps; wrap360_deg gives a compass heading.
  double heading_deg_at(double parameter) const;
  // Points along the curve from domain_min to domain_max (both included), consecutive points at
  // most max_step_m apart (chord). max_step_m may be +infinity.
  Polyline sample(double max_step_m) const;
  // As sample(max_step_m), and also every point of the curve between two consecutive samples is
  // within max_chord_error_m of the chord joining them (a rigorous bound from the derivatives).
  Polyline sample(double max_step_m, double max_chord_error_m) const;
  // Throws std::invalid_argument naming the inconsistent field; used when a fit is loaded.
  void check() const;
  friend bool operator==(const CurveFit&, const CurveFit&) = default;
};

struct ArcSplineOptions {
  // One knot interval per knot_spacing_m of path. Shorter intervals follow tight turns and the
  // curvature jump at the end of the lead-in more closely; longer ones average more samples per
  // control point. 1.25 m keeps a noise-free R = 2 m turn within ~2 cm (the junction) and below
  // 4 mm RMS; noise is handled by the penalty below rather than by coarser knots, which would
  // cost that fidelity on clean data.
  double knot_spacing_m = 1.25;
  std::size_t min_intervals = 2;
  std::size_t max_intervals = 40;
  // Weight (m^6) of the jerk integral |d3C/ds3|^2 ds against the squared residuals per metre of
  // path. Penalising the third rather than the second derivative leaves lines exact and circular
  // arcs nearly unbiased, in particular at the ends, where a bending penalty straightens the
  // curve and costs degrees of final heading. This floor (smoothing length 1e-5^(1/6) = 0.15 m)
  // only keeps the system full rank when a knot interval holds no samples.
  double smoothing_m6 = 1e-5;
  // Extra smoothing per unit of (sigma^2 * metres per sample)^(6/7), with sigma from
  // estimate_position_noise_m: noisy turns get a stiffer curve instead of one that wiggles
  // through the noise, clean ones keep the floor. 30 was chosen on synthetic turns of
  // 10-170 degrees with 0-0.3 m noise: at 0.3 m noise the spurious back-and-forth turning drops
  // from hundreds of degrees to under 1 degree on average and the error against the noise-free
  // path from 0.12-0.16 m to 0.07-0.10 m RMS. 0 disables it.
  double noise_smoothing_gain = 30.0;
  // Rounds of foot-point parameter correction: chord length of noisy samples is a poor
  // parameter (noise inflates it unevenly), so each round projects the samples on the last curve
  // and refits using their arc length position along it. One round removes the rare curve that
  // loops through bunched-up noisy samples; more changed nothing measurable on synthetic turns
  // and each costs about as much as the first fit.
  int parameter_iterations = 1;
};

// Robust per-coordinate position noise (m) of a densely sampled track, from the median size of
// third differences: the path's own shape contributes only ~step^3 / R^2 (about 1 mm at 0.25 m
// steps on R = 2 m), where second differences would mistake step^2 / R of curvature for noise.
double estimate_position_noise_m(const Polyline& points);

// Least squares on scaled x (column-pivoting Householder QR). Throws std::invalid_argument if
// there are fewer than 5 distinct x or a non-finite coordinate.
CurveFit fit_poly4(const Polyline& points);
// Throws std::invalid_argument for non-finite coordinates, fewer than 3 distinct points or
// inconsistent options.
CurveFit fit_arc_length_spline(const Polyline& points, const ArcSplineOptions& options = {});
CurveFit fit_curve(FitKind kind, const Polyline& points);

// RMS over points of the distance to the fitted curve (sampled so densely that the sampling error
// is below 0.1 mm).
double rms_distance_m(const Polyline& points, const CurveFit& fit);

// The poly4_xy coefficients a_k of y = sum_k a_k x^k in unscaled x (for reports in the thesis's
// form; badly conditioned far from the origin, so the fit itself keeps the scaled form).
std::array<double, kPoly4CoefficientCount> unscaled_poly4_coefficients(const CurveFit& fit);

}  // namespace avk::kinematics
