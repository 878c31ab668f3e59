#pragma once
// How a vehicle's speed moves after its commanded speed steps from u0 to u1:
// the fraction of the change done, phi(t), 0 at the command and 1 once settled, so one response
// serves any pair of speeds: u(t) = u0 + phi(t) (u1 - u0).
//
// Two sources: the black-box yaw model's speed model (yaw_model.hpp, a first-order lag), and the
// recorded speed of stored speed-change turns (the measured response). Both are first-order past
// their sampled window.

#include <optional>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::kinematics {

struct SpeedResponse {
  double dt_s = 0.1;
  std::vector<double> fraction;  // phi at t = k dt; [0] = 0
  // Past the samples phi approaches 1 as 1 - (1 - phi_end) exp(-(t - T) / tail_tau_s).
  double tail_tau_s = 1.0;
  std::size_t n_turns = 0;  // measured: the turns it was averaged from; 0 from a model

  double fraction_at(double t_s) const;
  double speed_at_mps(double t_s, double u0_mps, double u1_mps) const {
    return u0_mps + fraction_at(t_s) * (u1_mps - u0_mps);
  }
};

// The speed model's lag: u(k+1) = u(k) + gain (u1 - u(k)) gives phi(k) = 1 - (1 - gain)^k at the
// model's rate (its sag in turns is already in the constant-speed turn the response re-times, and
// its bias shifts u0 and u1 alike). Empty without a speed model or with a gain outside (0, 1].
std::optional<SpeedResponse> speed_response_of_model(const YawModel& model);

// A first-order response with time constant tau_s (a test's known profile).
SpeedResponse first_order_speed_response(double tau_s, double dt_s = 0.1);

// The mean phi of the ok turns that carry a speed change (each phi from its own recorded speed:
// (u(t) - u(0)) / (u1 - u0)), over the time the shortest of them covers; the tail's time constant
// is the first-order fit to that mean. Empty without such turns.
std::optional<SpeedResponse> measured_speed_response(const std::vector<TurnSequence>& turns,
                                                     double dt_s = 0.1);

}  // namespace avk::kinematics
