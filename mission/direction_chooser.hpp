#pragma once
// Direction `auto` (beyond the thesis): turn to the side whose predicted trajectory keeps the
// vehicle inside the region, so fewer turns are lost to containment. The prediction is the CKT
// built so far when it covers the speed, and the instantaneous-turn assumption (a ray along the
// goal heading) before then.

#include <optional>

#include "kinematics/ckt.hpp"
#include "kinematics/geometry.hpp"
#include "mission/container.hpp"

namespace avk::mission {

struct SideChoice {
  kinematics::TurnSide side = kinematics::TurnSide::right;
  double right_clearance_m = 0.0;  // least distance of the predicted path inside the boundary
  double left_clearance_m = 0.0;   // (negative: the path leaves the region)
  bool from_table = false;         // false: instantaneous assumption
};

struct DirectionOptions {
  // Straight run after the turn that must stay clear too: room to re-establish conditions.
  double run_out_s = 10.0;
  double min_run_out_m = 10.0;
};

// prefer: the side to take when both stay clear of the buffer (keeps left and right balanced).
SideChoice choose_side(const Container& container, const kinematics::Pose& start, double speed_mps,
                       double dheading_deg, const kinematics::Ckt* table,
                       kinematics::TurnSide prefer, const DirectionOptions& options = {});

}  // namespace avk::mission
