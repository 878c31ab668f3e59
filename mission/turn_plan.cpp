#include "mission/turn_plan.hpp"

#include <cmath>

#include "kinematics/ckt.hpp"

namespace avk::mission {

std::vector<TurnTask> plan_turns(const MissionConfig& config) {
  std::vector<TurnTask> plan;
  if (config.kind != MissionKind::turns) return plan;
  const auto& ta = config.turn_array;
  const std::vector<double> rates =
      ta.initial_yaw_rates_dps.empty() ? std::vector<double>{0.0} : ta.initial_yaw_rates_dps;
  // Constant-speed rows first, then the speed changes, each over every heading change.
  std::vector<std::pair<double, std::optional<double>>> rows;
  for (double u : ta.speeds_mps)
    rows.push_back({u, std::nullopt});
  for (const SpeedChange& c : ta.speed_changes)
    rows.push_back({c.from_mps, c.to_mps});
  for (const auto& [u, u1] : rows) {
    for (double d : ta.dheadings_deg) {
      for (std::size_t k = 0; k < rates.size() * static_cast<std::size_t>(ta.repeats); ++k) {
        TurnTask t;
        t.index = plan.size();
        t.speed_mps = u;
        t.speed_after_mps = u1;
        t.dheading_deg = d;
        t.initial_yaw_rate_dps = rates[k / static_cast<std::size_t>(ta.repeats)];
        switch (ta.direction) {
          case DirectionPolicy::right:
            t.side = kinematics::TurnSide::right;
            break;
          case DirectionPolicy::left:
            t.side = kinematics::TurnSide::left;
            break;
          case DirectionPolicy::alternate:
            t.side = t.index % 2 == 0 ? kinematics::TurnSide::right : kinematics::TurnSide::left;
            break;
          case DirectionPolicy::automatic:
            break;
        }
        plan.push_back(t);
      }
    }
  }
  return plan;
}

bool same_cell(double speed_a_mps, double dheading_a_deg, double speed_b_mps,
               double dheading_b_deg) {
  const kinematics::CktOptions tolerances;
  return kinematics::within_match(speed_a_mps, speed_b_mps, tolerances.speed_match_mps) &&
         kinematics::within_match(std::abs(dheading_a_deg), std::abs(dheading_b_deg),
                                  tolerances.dheading_match_deg);
}

bool same_cell(double speed_a_mps, std::optional<double> speed_after_a_mps, double dheading_a_deg,
               double speed_b_mps, std::optional<double> speed_after_b_mps, double dheading_b_deg) {
  if (speed_after_a_mps.has_value() != speed_after_b_mps.has_value()) return false;
  if (speed_after_a_mps && !kinematics::within_match(*speed_after_a_mps, *speed_after_b_mps,
                                                     kinematics::CktOptions{}.speed_match_mps))
    return false;
  return same_cell(speed_a_mps, dheading_a_deg, speed_b_mps, dheading_b_deg);
}

std::vector<TurnTask> remaining_turns(const std::vector<TurnTask>& plan,
                                      const std::vector<CellCount>& done) {
  std::vector<int> left_to_skip;
  for (const auto& c : done)
    left_to_skip.push_back(c.done);
  std::vector<TurnTask> out;
  for (const auto& t : plan) {
    bool skipped = false;
    for (std::size_t i = 0; i < done.size() && !skipped; ++i) {
      if (left_to_skip[i] > 0 &&
          same_cell(t.speed_mps, t.speed_after_mps, t.dheading_deg, done[i].speed_mps,
                    done[i].speed_after_mps, done[i].dheading_deg)) {
        --left_to_skip[i];
        skipped = true;
      }
    }
    if (!skipped) out.push_back(t);
  }
  return out;
}

}  // namespace avk::mission
