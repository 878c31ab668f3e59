#pragma once
// The helm modes of the collection mission (thesis §4.5), as MOOS' helm mode tree names them,
// and those of a vehicle no mission drives (mission/command_helm.hpp).

#include <optional>
#include <string_view>
#include <vector>

namespace avk::mission {

enum class HelmMode {
  containing,    // in the buffer (or not yet inside): heading for the region's interior
  conditioning,  // ConditionSet: hold the noted course, reach the target speed
  turning,       // ConstantHeading + ConstantSpeed: the recorded turn
  exciting,      // persistent excitation: random heading steps at constant speed
  returning,     // all turns done: to the return point
  paused,        // all stop, waiting for resume
  done,          // at the return point, all stop
  halted,        // all stop after leaving the region or an operator abort
  // No mission: the operator's command, or the hold at a mission's return point after it ended.
  transiting,  // heading for the point to hold
  holding,     // station keeping at the point
  stopped,     // all stop by the operator's command
};
const char* to_string(HelmMode m);
std::optional<HelmMode> helm_mode_from_string(std::string_view s);
// Every mode, in declaration order.
const std::vector<HelmMode>& all_helm_modes();

// What navigation imported from a log records as its helm mode: the helm state is unknown, so it
// is treated as guided (identification uses it).
inline constexpr std::string_view kImportedHelmMode = "IMPORTED";

// Modes in which the helm commands a heading and speed.
bool commands_motion(HelmMode m);

}  // namespace avk::mission
