#pragma once
// Piecewise-linear approximation of trajectories (thesis §3.3.2: the fitted curve is replaced by a
// polyline so guidance can work with segments).

#include "kinematics/curve_fit.hpp"
#include "kinematics/geometry.hpp"

namespace avk::kinematics {

// Douglas–Peucker with an explicit stack (a long dense track must not exhaust the call stack).
// Keeps both ends; every input point is within epsilon_m of the result, whose vertices are a
// subset of the input. Throws std::invalid_argument for a negative or NaN epsilon_m.
Polyline simplify_polyline(const Polyline& dense, double epsilon_m);

// Vertices on the fitted curve such that no point of the curve is more than epsilon_m from the
// polyline. The curve is sampled so that its chords stray at most epsilon_m / 8 from it (bound
// from the derivatives), and those samples are simplified with the remaining 7/8 of epsilon_m.
// Throws std::invalid_argument unless epsilon_m > 0.
Polyline piecewise_linear(const CurveFit& fit, double epsilon_m = 0.05);

// Max over reference points of the distance to approx (infinity if approx is empty, 0 if
// reference is). O(reference * approx): meant for checks, not for hot paths.
double max_deviation_m(const Polyline& reference, const Polyline& approx);

}  // namespace avk::kinematics
