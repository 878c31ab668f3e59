#pragma once
// What the current estimates read from a stored mission: its turns a page at a time, and the
// steady legs its navigation flew before each turn. For app/ only (it reads store rows).

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "app/current.hpp"
#include "kinematics/current_estimate.hpp"
#include "store/store.hpp"

namespace avk::app {

// Calls fn for every stored turn row of a mission (of one status when given), oldest first, a
// page at a time.
void for_each_mission_turn(store::Store& db, std::int64_t mission_id,
                           std::optional<kinematics::TurnStatus> status,
                           const std::function<void(const store::TurnRow&)>& fn);

// The steady legs of a mission's navigation: for each turn start time, the rows before it whose
// desired heading and speed equal those in force at the command, at most leg_s long and at least
// kMinSteadyLegS. The held heading is the legs' circular mean compass heading; the speed through
// the water is the desired speed.
std::vector<kinematics::SteadyLeg> steady_legs_before(const std::vector<double>& turn_starts_s,
                                                      const std::vector<store::NavRow>& nav,
                                                      double leg_s = kSteadyLegS);

// The legs that measure the vehicle's motion (which speed its loop holds and how its straight-line
// predictions scatter, app/vehicle_motion.hpp) are longer than the current's: the whole stretch
// before each command during which the guidance held (as for steady_legs_before) and the vehicle
// was steady, at most kMotionLegMaxS and at least kMotionLegMinS. Steady: its heading and its
// speed over ground, each averaged over kSteadySmoothingS, within kSteadyHeadingTolDeg and
// kSteadySpeedTolMps of their means over the last kSteadyReferenceS before the command. The first
// seconds after a heading change are the last turn's tail and the speed loop's recovery, and are
// left out so. On a steady leg the speed over ground is constant whichever speed the loop holds,
// so the test favours neither.
inline constexpr double kMotionLegMaxS = 60.0;
inline constexpr double kMotionLegMinS = 5.0;
inline constexpr double kSteadyReferenceS = 3.0;
inline constexpr double kSteadySmoothingS = 1.0;
inline constexpr double kSteadyHeadingTolDeg = 8.0;
inline constexpr double kSteadySpeedTolMps = 0.05;
std::vector<kinematics::SteadyLeg> steady_stretches_before(const std::vector<double>& turn_starts_s,
                                                           const std::vector<store::NavRow>& nav);

}  // namespace avk::app
