#pragma once
// Scalar summaries of one turn: the thesis's advance and transfer (§3.1, Figures 5-4/5-5) and the
// IMO MSC.137(76) manoeuvring measures, so a stored turn can be compared with ship practice.
//
// Everything is measured on the normalised turn (start at the origin heading north, turning right),
// so a left turn and its mirror image give identical measures and "transfer" is always positive
// towards the turn side.

#include <optional>

#include "kinematics/geometry.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::kinematics {

struct AdvanceTransfer {
  double advance_m = 0.0;   // along the original course
  double transfer_m = 0.0;  // across it, + towards the turn side
};

// Thesis §3.1: displacement along (advance) and across (transfer, + to the turn side) the original
// course at the end of the turn; for a normalised turn that is (y_end, x_end). Measured from the
// first point, which is the origin for a normalised turn. Throws std::invalid_argument when empty.
AdvanceTransfer advance_transfer(const Polyline& normalized);
// Normalises the turn first unless it already is. Throws std::invalid_argument when empty.
AdvanceTransfer advance_transfer(const TurnSequence& turn);

// Tunables of measure_turn. The defaults suit the 4-10 Hz navigation of small USVs.
struct TurnMeasureOptions {
  // "Steady" turning: the longest (in time) run of consecutive sample intervals whose yaw rate,
  // after a 3-point running median (one noisy heading fix must not split a run), stays within
  // +-steady_yaw_tolerance of the run's mid-range, i.e. max*(1-tol) <= min*(1+tol), with every
  // rate at least min_steady_yaw_rate_dps towards the turn. The run must span at least
  // min_steady_intervals intervals and min_steady_dheading_deg of heading change, otherwise the
  // turn is never steady and the radius is absent.
  double steady_yaw_tolerance = 0.10;
  double min_steady_yaw_rate_dps = 1.0;
  int min_steady_intervals = 3;
  double min_steady_dheading_deg = 10.0;
  // A turn whose largest heading change comes within this of |goal| has reached its goal (a
  // controller may settle a fraction of a degree short); the same tolerance as the validator's
  // instantaneous-turn check.
  double goal_reached_tolerance_deg = 0.5;
};

// IMO MSC.137(76) manoeuvring measures. Optional members are std::nullopt (absent, not zero) when
// the turn does not reach the heading that defines them. Heading crossings are the *first* sample
// interval where the heading change reaches the target, interpolated linearly between the two
// samples by heading, so a later noisy dip below the target does not move them.
struct TurnMeasures {
  AdvanceTransfer at_end;
  std::optional<double> advance_90_m;         // advance at 90 deg heading change
  std::optional<double> transfer_90_m;        // transfer at 90 deg heading change
  std::optional<double> tactical_diameter_m;  // transfer at 180 deg heading change
  // Mean speed over mean yaw rate on the steady part (TurnMeasureOptions), i.e. the radius of the
  // turning circle the vehicle would fly if it held that yaw rate. Uses the recorded speeds (not
  // position differences, which position noise inflates).
  std::optional<double> steady_turning_radius_m;
  std::optional<double> steady_yaw_rate_dps;  // the yaw rate that radius was computed from
  std::optional<double> time_to_90_s;         // from the first sample
  std::optional<double> time_to_180_s;
  // Initial (first sample) speed minus the minimum speed during the turn; absent when the first
  // sample has no positive speed (speed not recorded).
  std::optional<double> speed_loss_mps;
  std::optional<double> speed_loss_fraction;        // speed_loss_mps / initial speed
  std::optional<double> distance_to_first_10deg_m;  // path length until 10 deg of heading change
  // Largest heading change beyond |goal|: 0 when none, absent when the goal was never reached or
  // is unknown (0).
  std::optional<double> overshoot_deg;
  std::optional<double>
      max_dheading_deg;  // largest heading change seen (present when >= 2 samples)
  std::optional<double> vehicle_length_m;  // copied from the argument, for in_vehicle_lengths
};

// Throws std::invalid_argument for a turn with fewer than 2 samples.
TurnMeasures measure_turn(const TurnSequence& turn, std::optional<double> vehicle_length_m = {});
TurnMeasures measure_turn(const TurnSequence& turn, const TurnMeasureOptions& options,
                          std::optional<double> vehicle_length_m = {});

// A length in vehicle lengths; absent when either is absent or the vehicle length is not positive.
std::optional<double> in_vehicle_lengths(std::optional<double> metres,
                                         std::optional<double> vehicle_length_m);

}  // namespace avk::kinematics
