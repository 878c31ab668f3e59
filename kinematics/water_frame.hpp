#pragma once
// Turns and predictions in a current (thesis §6.3).
//
// The CKT describes how the hull turns through the water. In a uniform current c everything the
// vehicle does through the water is carried along at c, so an observed turn over ground is its
// water-relative path plus c·(t − t0). Taking the drift out of the recorded turns lets a table
// learned in one current predict turns in another; adding the drift of the current at the time of
// a query puts the prediction back over ground, where guidance needs it.

#include <optional>

#include "kinematics/geometry.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/path_metric.hpp"
#include "kinematics/turn_sequence.hpp"
#include "kinematics/turn_timing.hpp"
#include "kinematics/water_current.hpp"

namespace avk::kinematics {

// The turn with the drift of the current removed: each position moved back by c·(t − t0), so the
// path is the one the vehicle made through the water; meta().removed_current records c.
// Headings are the compass's (the hull's orientation, which the current does not change). Speeds
// become the speed through the water along the heading, taken as the speed over ground less the
// current's component along the heading (a station records speed, not course, over ground).
// Throws std::invalid_argument for a normalised turn (the current is in the grid frame, the
// normalised turn's is not), a turn already in the water frame, or a non-finite current.
TurnSequence in_water_frame(const TurnSequence& raw, WaterCurrent c);

// The current seen in a turn's normalised frame: rotated so the initial heading points north,
// mirrored for a left turn (as TurnSequence::normalized moves the positions).
Point current_in_normalized_frame(WaterCurrent c, double initial_heading_deg, TurnSide side);

// A path carried by a uniform velocity (m/s, in the path's frame): each point moved by v·t.
// What a vehicle whose speed loop holds its speed through the water does in a current.
TimedPath drifted(TimedPath path, Point velocity_mps);

// The scale k of a velocity through the water u at which a vehicle in current c makes good
// |u| over ground: |k·u + c| = |u|, the larger root. A current too strong for that (no root,
// or a root that would need more than kMaxOverGroundScale times the speed) gives the bound
// nearest to a solution: the vehicle's speed loop saturates.
inline constexpr double kMinOverGroundScale = 0.25;
inline constexpr double kMaxOverGroundScale = 4.0;
double over_ground_scale(Point water_velocity_mps, Point current_mps);

// What a vehicle whose speed loop holds its speed OVER GROUND does in a current (the M200's
// pMarinePID on GNSS speed): it flies the same path through the water, but each segment at the
// speed through the water that makes the segment's still-water speed good over ground, so the
// segment takes dt/k (over_ground_scale) and is carried by c over that time. Points stay one
// for one with the input; times are re-timed from the first point's.
TimedPath retimed_over_ground(const TimedPath& water_path, Point current_mps);

// A trajectory through the water (the normalised frame of a prediction) carried by a current
// given in that frame: each vertex moved by v·t, with t from the timing when there is one, else
// at constant speed (timed_maneuver's rule). Throws std::invalid_argument for a speed not > 0.
Polyline drifted_trajectory(const Polyline& trajectory, const std::optional<TurnTiming>& timing,
                            double speed_mps, Point velocity_mps);

// A timed path stationed by its clock, s = speed × t: the stations an observed turn gets
// (path_metric.hpp stationed_by_time), so a prediction moved by a current compares with observed
// turns point for point in time. Throws std::invalid_argument for an empty path or a speed not
// > 0.
StationedPath stationed_by_clock(const TimedPath& path, double speed_mps);

}  // namespace avk::kinematics
