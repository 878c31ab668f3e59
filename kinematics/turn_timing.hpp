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
//
// The corridor (corridor.hpp) says how far to either side a turn strays; the along-track spread
// says how far ahead or behind it is: at each station, the sample standard deviation across the
// cell's turns of the time each turn passed it, every turn projected onto the trajectory exactly
// as the mean is. A vehicle that slows by a varying amount in its turns has a wide spread even
// when every turn follows the same path.

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
  // Empty (no spread known: a single turn, an older table file) or kTimingStations values >= 0 at
  // the same fractions: the sample sd across the cell's turns of the time each passed there.
  std::vector<double> time_sd_s;
  friend bool operator==(const TurnTiming&, const TurnTiming&) = default;
};

// The timing of a cell's trajectory from its mean turn stationed by time at commanded_speed_mps
// (mean.s_m / speed is the time of each point): each mean point is projected onto the trajectory
// (forward only, so a curling path is followed in order), the lengths are made non-decreasing,
// and the trajectory past the projection of the mean's last point is run at the commanded speed.
// Empty when the trajectory or the mean has fewer than 2 points or the speed is not > 0.
std::optional<TurnTiming> timing_of(const StationedPath& mean_by_time, double commanded_speed_mps,
                                    const Polyline& trajectory);

// The along-track spread of a cell's turns, each stationed by time at commanded_speed_mps
// (stationed_by_time): every turn is timed along the trajectory as timing_of times the mean
// (forward-only projection, lengths non-decreasing, past its end at the commanded speed), and the
// sample standard deviation of the turns' times is taken at each of the kTimingStations stations.
// Turns are first densified to kStationStep_m so that sparse fixes cannot outrun the forward
// search. Empty when fewer than 2 turns can be timed (or the trajectory or speed cannot be).
std::vector<double> timing_spread_s(const std::vector<StationedPath>& turns_by_time,
                                    double commanded_speed_mps, const Polyline& trajectory);

// A constant-speed timing of a path of this length: what a table without recorded timing (a CKT
// file of schema 1 or 2) answers.
TurnTiming constant_speed_timing(double length_m, double speed_mps);

// The time at which the path reaches length l: interpolated between stations; past the end at
// end_speed_mps. Throws std::invalid_argument for a timing without stations or a speed not > 0
// when it is needed.
double time_at_length_s(const TurnTiming& timing, double l_m, double end_speed_mps);

// The along-track sd at length l: linear between stations, the last value past the end, 0 when the
// timing has no spread.
double time_sd_at_length_s(const TurnTiming& timing, double l_m);

// The blend of cell timings with weights summing to 1, at equal fractions; length weighted. The
// spreads are weighted likewise (as the corridor blends its sd); the blend has none when a source
// has none. Empty when any source is empty.
std::optional<TurnTiming> blend_timings(
    const std::vector<std::pair<const std::optional<TurnTiming>*, double>>& sources);

// The same timing stretched to a path of new_length_m at the same mean speed (a turn the table
// carries beyond its range is longer than the cell it is carried from): times and their spread
// scale with the length.
TurnTiming scaled_timing(const TurnTiming& timing, double new_length_m);

}  // namespace avk::kinematics
