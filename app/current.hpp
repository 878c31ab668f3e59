#pragma once
// The current a mission flew in, estimated from its own navigation (issue 17, part 3: the first
// piece): the steady legs before each turn, where the ConditionSet held course and speed, give the
// velocity over ground on many headings (kinematics/current_estimate.hpp).

#include <cstdint>
#include <vector>

#include "app/result.hpp"
#include "kinematics/current_estimate.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

// How much of the steady stretch before each turn is used: the last leg_s seconds before the
// command during which the desired heading and speed stayed as they were at the command.
inline constexpr double kSteadyLegS = 8.0;
inline constexpr double kMinSteadyLegS = 3.0;

struct MissionCurrent {
  std::int64_t mission_id = 0;
  std::size_t turns = 0;      // turns of the mission
  std::size_t legs_used = 0;  // steady legs found before them
  kinematics::CurrentEstimateResult result;
};

// not_found for an unknown mission.
Result<MissionCurrent> estimate_mission_current(Context& ctx, std::int64_t mission_id,
                                                double leg_s = kSteadyLegS);

// The steady legs of a mission's navigation: for each turn start time, the rows before it whose
// desired heading and speed equal those in force at the command, at most leg_s long and at least
// kMinSteadyLegS. The held heading is the legs' circular mean compass heading; the speed through
// the water is the desired speed.
std::vector<kinematics::SteadyLeg> steady_legs_before(const std::vector<double>& turn_starts_s,
                                                      const std::vector<store::NavRow>& nav,
                                                      double leg_s = kSteadyLegS);

}  // namespace avk::app
