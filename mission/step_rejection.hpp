#pragma once
// Why a step of the desired heading in a navigation log gave no usable turn: the fixed list the
// harvester (mission/turn_harvester.hpp) counts by, documented in docs/harvest.md.

#include <array>
#include <optional>
#include <string_view>

namespace avk::mission {

enum class StepRejection {
  log_gap,                   // a navigation gap before the step or during the turn
  too_small,                 // the goal (new desired heading - heading) under min_step_deg
  speed_command_changed,     // the desired speed changed at the step or during the turn
  not_steady_before,         // too little steady history, or the yaw rate was not steady
  course_not_held,           // the desired heading was not held over the window (a bearing)
  speed_not_steady,          // the speed was not within tolerance of the desired speed
  goal_changed_during_turn,  // the desired heading changed before completion
  never_completed,           // timed out, or the log ended during the turn
  instantaneous,             // initial and final headings (nearly) the same
  too_short,                 // too few samples to be a trajectory
  wrong_way,                 // turned against the goal
  stopped_short,             // ended short of the completion threshold
  bad_samples,               // non-finite values or time not increasing
};

inline constexpr std::size_t kStepRejectionCount = 13;
inline constexpr std::array<std::string_view, kStepRejectionCount> kStepRejectionNames = {
    "log_gap",
    "too_small",
    "speed_command_changed",
    "not_steady_before",
    "course_not_held",
    "speed_not_steady",
    "goal_changed_during_turn",
    "never_completed",
    "instantaneous",
    "too_short",
    "wrong_way",
    "stopped_short",
    "bad_samples"};

inline std::string_view to_string(StepRejection r) {
  return kStepRejectionNames[static_cast<std::size_t>(r)];
}

inline std::optional<StepRejection> step_rejection_from_string(std::string_view s) {
  for (std::size_t i = 0; i < kStepRejectionCount; ++i)
    if (kStepRejectionNames[i] == s) return static_cast<StepRejection>(i);
  return std::nullopt;
}

}  // namespace avk::mission
