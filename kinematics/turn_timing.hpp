#pragma once
// When a predicted turn reaches each point of its path.
//
// A CKT trajectory is geometry only, but choosing a maneuver by closest point of approach needs
// to know where the vehicle is at each time. The time comes from the recorded turns: the mean
// turn at equal stations s = commanded speed × t (path_metric.hpp) is a mean position per time, so
// projecting it onto the cell's trajectory gives the time at which the vehicle, on average, passes
// each point of the trajectory. A vehicle that slows in its turns is therefore later along its
// path than a constant-speed one would be.
//
// Times are kept at equal fractions of the trajectory's length so that cells blend as their
// trajectories do (interpolation over fraction of arc length), like the corridor.

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/path_metric.hpp"

namespace avk::kinematics {

inline constexpr std::size_t kTimingStations = 101;

struct TurnTiming {
  double length_m = 0.0;       // the length of the trajectory the times are along
  std::vector<double> time_s;  // kTimingStations values at fractions 0..1; [0] = 0, non-decreasing
  friend bool operator==(const TurnTiming&, const TurnTiming&) = default;
};

// The timing of a cell's trajectory from its mean turn stationed by time at commanded_speed_mps
// (mean.s_m / speed is the time of each point): each mean point is projected onto the trajectory
// (forward only, so a curling path is followed in order), the lengths are made non-decreasing,
// and the trajectory past the projection of the mean's last point is run at the commanded speed.
// Empty when the trajectory or the mean has fewer than 2 points or the speed is not > 0.
std::optional<TurnTiming> timing_of(const StationedPath& mean_by_time, double commanded_speed_mps,
                                    const Polyline& trajectory);

// A constant-speed timing of a path of this length: what a table without recorded timing (a CKT
// file of schema 1 or 2) answers.
TurnTiming constant_speed_timing(double length_m, double speed_mps);

// The time at which the path reaches length l: interpolated between stations; past the end at
// end_speed_mps. Throws std::invalid_argument for a timing without stations or a speed not > 0
// when it is needed.
double time_at_length_s(const TurnTiming& timing, double l_m, double end_speed_mps);

// The blend of cell timings with weights summing to 1, at equal fractions; length weighted.
// Empty when any source is empty.
std::optional<TurnTiming> blend_timings(
    const std::vector<std::pair<const std::optional<TurnTiming>*, double>>& sources);

// The same timing stretched to a path of new_length_m at the same mean speed (a turn the table
// carries beyond its range is longer than the cell it is carried from).
TurnTiming scaled_timing(const TurnTiming& timing, double new_length_m);

}  // namespace avk::kinematics
