#pragma once
// The current a mission flew in as the station last estimated it: what front ends show and the
// live feed publishes (the front ends' type, not the store's row: app/mission_views.hpp).

#include <cstdint>
#include <optional>
#include <string>

#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"

namespace avk::app {

struct CurrentView {
  std::int64_t mission_id = 0;
  double t_s = 0.0;             // station clock: the end of the newest evidence used
  std::string method = "legs";  // legs (steady legs before turns) or turns (turn residuals)
  kinematics::CurrentEstimate estimate;
  std::int64_t revision = 0;  // grows with every estimate stored: tells a cache it changed
  // Judged from the mission's steady legs in this current; none when not evaluated or, for the
  // scatter, from too few legs.
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference;
  std::optional<kinematics::DriftScatter> drift_scatter;
};

}  // namespace avk::app
