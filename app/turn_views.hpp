#pragma once
// What the use cases answer about recorded turns, and how a front end asks for them. The front
// ends' types, not the store's rows (app/mission_views.hpp says why).

#include <cstdint>
#include <optional>
#include <string>

#include "kinematics/turn_sequence.hpp"

namespace avk::app {

// A turn's summary, readable without its trajectories.
struct TurnView {
  std::int64_t id = 0;
  std::int64_t mission_id = 0;
  std::string vehicle_id;
  double cell_speed_mps = 0.0;     // the turn-array cell: commanded speed
  double cell_dheading_deg = 0.0;  // and |goal|: the table stores right turns
  kinematics::TurnStatus status = kinematics::TurnStatus::ok;
  std::string reason;
  double commanded_speed_mps = 0.0;
  double goal_dheading_deg = 0.0;  // signed
  double observed_dheading_deg = 0.0;
  double start_time_s = 0.0;  // mission clock
  double end_time_s = 0.0;
  std::optional<double> advance_m;  // none when the turn could not be normalised
  std::optional<double> transfer_m;
  std::optional<double> condition_set_time_s;
  std::optional<double> start_heading_error_deg;  // how steady it began
  std::optional<double> start_yaw_rate_dps;
  kinematics::TurnSource source = kinematics::TurnSource::collection;
  std::optional<double> quality;          // harvested turns
  std::optional<double> speed_after_mps;  // u1 of a speed-change turn
};

// A turn with its trajectories: as navigated, and normalised (none when it could not be).
struct TurnDetail {
  TurnView row;
  kinematics::TurnSequence raw;
  std::optional<kinematics::TurnSequence> normalized;
};

// Which turns a listing shows: keyset pages of ids after after_id, oldest first.
struct TurnQuery {
  std::optional<std::int64_t> mission_id;
  std::optional<double> speed_mps;     // the commanded speed within speed_tolerance_mps
  std::optional<double> dheading_deg;  // the signed goal within dheading_tolerance_deg
  std::optional<kinematics::TurnStatus> status;
  double speed_tolerance_mps = 0.05;
  double dheading_tolerance_deg = 0.5;
  std::int64_t after_id = 0;
  int limit = 100;
};

}  // namespace avk::app
