#pragma once
// The probability that a predicted approach comes closer than the standoff, from the own
// vehicle's position band and the contact's uncertainty.
//
// The miss distance m(e) = min over t of |r(t) + e(t)| for a position error e. To first order
// about the predicted closest approach at t* (the envelope theorem: the time of the minimum
// moves, but the minimum changes only through e), m ≈ m₀ + n·e(t*) with n the unit vector from
// the contact to the own vehicle at t*. With e normal of covariance C(t*) (own band plus the
// contact's), n·e is normal with variance σ² = n'Cn, and the miss is below the standoff d when
// −d − m₀ < n·e < d − m₀:
//     P = Φ((d − m₀)/σ) − Φ((−d − m₀)/σ).
// A path with several approaches (a curling turn) takes the largest over its segments' closest
// approaches: their errors are strongly correlated in time (a late turn stays late), so the
// largest is a better figure than their sum.

#include <vector>

#include "kinematics/maneuver.hpp"
#include "kinematics/position_band.hpp"

namespace avk::kinematics {

// The contact's own position covariance at time t_s: its position sd, and its course and speed
// sd carried over t_s (along and across its course).
Covariance2 contact_covariance(const Contact& c, double t_s);

// P(the closest approach < standoff_m). own_covariance holds one band per path point (linear in
// between along a segment). An exactly known approach (no spread) gives 0 or 1. Throws
// std::invalid_argument for an empty path or covariances of the wrong size.
double approach_risk(const TimedPath& own, const std::vector<Covariance2>& own_covariance,
                     const Contact& contact, double standoff_m);

}  // namespace avk::kinematics
