#include "mission/turn_checks.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "mission/turn_monitor.hpp"

namespace avk::mission {

namespace {
std::string num(double v) {
  return nlohmann::json(std::round(v * 100.0) / 100.0).dump();
}
StepRejection kind_of(kinematics::TurnErrorCode code) {
  switch (code) {
    case kinematics::TurnErrorCode::instantaneous_turn:
      return StepRejection::instantaneous;
    case kinematics::TurnErrorCode::too_few_samples:
      return StepRejection::too_short;
    default:
      return StepRejection::bad_samples;
  }
}

}  // namespace

std::optional<std::string> turn_anomaly(const kinematics::TurnSequence& raw,
                                        const TurnCheckOptions& options) {
  auto a = find_turn_anomaly(raw, options);
  if (!a) return std::nullopt;
  return std::move(a->reason);
}

std::optional<TurnAnomaly> find_turn_anomaly(const kinematics::TurnSequence& raw,
                                             const TurnCheckOptions& options) {
  try {
    raw.validate();
  } catch (const kinematics::TurnError& e) {
    return TurnAnomaly{kind_of(e.code()),
                       std::string(kinematics::to_string(e.code())) + ": " + e.what()};
  }
  const auto& s = raw.samples();
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i].t_s - s[i - 1].t_s > options.max_sample_gap_s) {
      return TurnAnomaly{StepRejection::log_gap, "navigation gap of " +
                                                     num(s[i].t_s - s[i - 1].t_s) +
                                                     " s at sample " + std::to_string(i)};
    }
  }
  const double goal = raw.meta().goal_dheading_deg;
  const double observed = raw.heading_change_deg();
  if (goal * observed <= 0.0) {
    return TurnAnomaly{StepRejection::wrong_way, "turned the wrong way: observed " + num(observed) +
                                                     " deg for a goal of " + num(goal) + " deg"};
  }
  // Completion is within the threshold of the goal, or past it; anything shorter is a turn that
  // ended for another reason and would enter the table as a smaller heading change. The threshold
  // is the goal's own (the monitor's), so a 10 deg turn may stop at most 2 deg short, not 6.
  if (std::abs(goal) - std::abs(observed) >
      completion_threshold_deg(options.completion, goal) + 1.0) {
    return TurnAnomaly{
        StepRejection::stopped_short,
        "stopped short: observed " + num(observed) + " deg for a goal of " + num(goal) + " deg"};
  }
  return std::nullopt;
}

}  // namespace avk::mission
