#pragma once
// The closest approach of two moving vehicles that both follow predicted paths (a turn each, or
// a course): unlike a contact on a straight line, either may be turning. Used to watch a fleet's
// vehicles against each other.

#include <vector>

#include "kinematics/maneuver.hpp"
#include "kinematics/timed_path.hpp"

namespace avk::kinematics {

// The closest approach of a and b over the time both paths span (exact: on each interval between
// the two paths' points the relative motion is linear). With half widths (one per point of their
// path, or empty for none), the distance is that between the two corridors' nearer edges: less
// both half widths at that time, floored at 0. Throws std::invalid_argument for an empty path,
// half widths that do not match their path, or paths whose times do not overlap.
Approach closest_approach(const TimedPath& a, const TimedPath& b,
                          const std::vector<double>& a_half_width_m = {},
                          const std::vector<double>& b_half_width_m = {});

// The point of the path at time t (held at its ends outside it). The path must not be empty.
TimedPoint position_at(const TimedPath& path, double t_s);

}  // namespace avk::kinematics
