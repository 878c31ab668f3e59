#pragma once
// A constant-speed turn re-timed by a speed change: how a speed-change turn is predicted where
// no measured cell of its pair exists (speed_change_table.hpp).
//
// The constant-speed turn (a CKT answer at u0) says where the vehicle heads at each time: its
// timing (turn_timing.hpp) gives the time at each length along the trajectory, so each segment's
// heading holds over a known interval of time. The heading over time is kept (the yaw response is
// taken as the constant-speed turn's) and the path is integrated again with the speed scaled by
// the speed response:
//   x(t) = integral v(t) (sin psi(t), cos psi(t)) dt,  v(t) = v_turn(t) u(t) / u0,
// where v_turn is the constant-speed turn's own speed along its path (its slowing in the turn)
// and u(t) = u0 + phi(t) (u1 - u0) the speed response. With u1 = u0 it is the constant-speed turn.

#include "kinematics/ckt.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/speed_response.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

struct RetimedTurn {
  Polyline trajectory;         // one vertex per vertex of the constant-speed turn
  std::vector<double> time_s;  // when each vertex is passed (the constant-speed turn's times)
  TurnTiming timing;           // the same at equal fractions of the new length
  // Where the re-timed turn ends: the end of its trajectory, or for a CKT answer the point of the
  // table's advance and transfer (where its turns ended) carried to the re-timed trajectory.
  double advance_m = 0.0;
  double transfer_m = 0.0;  // + towards the turn side
};

// trajectory: the constant-speed turn, from the origin (either side); timing: when it passes its
// points (empty: constant speed u0). Throws std::invalid_argument for speeds not > 0 or a
// trajectory of fewer than 2 points.
RetimedTurn retime_turn(const Polyline& trajectory, const std::optional<TurnTiming>& timing,
                        double u0_mps, double u1_mps, const SpeedResponse& response);

// The same for a CKT answer (its trajectory and timing; advance and transfer as above).
RetimedTurn retime_turn(const TurnPrediction& constant_speed, double u0_mps, double u1_mps,
                        const SpeedResponse& response);

}  // namespace avk::kinematics
