#pragma once
// Paths compared at equal arc length, the metric that replaces y(x) as the default.
//
// The thesis reads y at equal x (§5.2). A shallow turn rises at cot(Δψ), so centimetres in where
// it ends in x become metres in y: the 1.5 m/s, 10° cell scored ~1160 m² for every method alike.
// Here two paths are compared point by point at equal arc length ("station"), and the score is
// their mean distance in metres, which stays on the scale of the paths themselves.
//
// Stations of an observed turn come from its clock, s = commanded speed × (t − t0), not from the
// length of its polyline: GNSS noise zigzags a recorded path and would stretch it, so two turns
// that went the same way would drift apart along track. A predicted path (the instantaneous ray,
// a model simulated at the commanded speed, a table trajectory) has no noise and takes its
// geometric length, which for a constant-speed prediction is the same thing.
//
// Past its last station every path continues along its goal heading, as the CKT's trajectories
// do, so paths of different lengths are compared over one common span (the longest turn of a
// cell).

#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::kinematics {

// A path in the normalised frame (start at the origin, heading north, a right turn) with the
// station (m) of each point, non-decreasing from 0.
struct StationedPath {
  std::vector<double> s_m;
  Polyline points;
  double length_m() const { return s_m.empty() ? 0.0 : s_m.back(); }
};

// Default station step of the metric and of the mean turn (m).
inline constexpr double kStationStep_m = 0.05;

// An observed turn's path, stationed by its clock at its commanded speed. The turn is normalised
// first when it is not. Throws std::invalid_argument when the commanded speed is not > 0, and
// TurnError as normalisation does.
StationedPath stationed_by_time(const TurnSequence& turn);

// A predicted path stationed by its geometric length. Throws std::invalid_argument when empty.
StationedPath stationed_by_length(const Polyline& path);

// The point at station s: interpolated between the stations around it, and past the last one
// along the goal heading |goal_dheading_deg| (a right turn) from the last point.
Point point_at_station(const StationedPath& path, double s_m, double goal_dheading_deg);

// Points at s = 0, step, 2 step, ... up to s_max_m (the last within 1e-9 step past it counts).
// Throws std::invalid_argument for a non-positive step, a negative or non-finite s_max_m, or more
// than kMaxXGridPoints stations.
Polyline points_at_stations(const StationedPath& path, double goal_dheading_deg, double s_max_m,
                            double step_m = kStationStep_m);

// Mean distance (m) between two paths at equal stations over [0, s_max_m].
double mean_path_distance_m(const StationedPath& a, const StationedPath& b,
                            double goal_dheading_deg, double s_max_m,
                            double step_m = kStationStep_m);

// The instantaneous-turn assumption as a path: the ray from the origin along the goal heading.
StationedPath instantaneous_path();

// The mean of paths at equal stations: each continued along the goal heading to the longest of
// them, x and y averaged per station. Throws std::invalid_argument for no paths or an empty one.
StationedPath mean_path_at_stations(const std::vector<StationedPath>& paths,
                                    double goal_dheading_deg, double step_m = kStationStep_m);

// The longest path's length.
double longest_m(const std::vector<StationedPath>& paths);

}  // namespace avk::kinematics
