#pragma once
// Choosing a maneuver by risk: each candidate's probability that its closest approach to some
// contact falls below the standoff (CandidateEvaluation::risk, approach_risk.hpp).
//
// The rule: the smallest |Δψ| whose risk is at most max_risk; between equal |Δψ|, starboard.
// Keeping course (Δψ = 0) is the smallest of all, so it is chosen exactly when its own risk is
// within the limit. When no candidate is within it, the least risky one (the smallest |Δψ| among
// equals), and the answer says the limit was not met.
//
// With prefer_starboard (COLREGS rules 14 and 15), when some contact that the held course would
// endanger is met head-on or crossing from starboard, only starboard turns (and the held course)
// are considered first; if none is within the limit, every candidate is, and the answer says so.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/colregs.hpp"
#include "kinematics/maneuver.hpp"

namespace avk::kinematics {

inline constexpr double kDefaultMaxRisk = 0.05;

struct ChoiceRule {
  double max_risk = kDefaultMaxRisk;
  bool prefer_starboard = false;  // COLREGS rules 14 and 15
};

struct ManeuverChoice {
  std::optional<std::size_t> index;  // into the candidates; none only without candidates
  bool within_limit = false;         // the chosen candidate's risk <= max_risk
  // The candidate's margin: its predicted CPA less the standoff (m), and its risk.
  double margin_m = 0.0;
  double risk = 0.0;
  // The situation with each contact the held course endangers (empty without COLREGS), and the
  // rule applied: "14" or "15" when the choice was kept to starboard, "" otherwise.
  std::vector<Situation> situations;
  std::string colregs_rule;
  std::string explanation;  // one sentence: what the rule did
};

// Throws std::invalid_argument for a max_risk outside [0, 1]. The contacts and own pose are the
// problem's; `held` indexes the candidate with Δψ = 0 when there is one.
ManeuverChoice choose_by_risk(const ManeuverProblem& problem, double own_speed_mps,
                              const std::vector<CandidateEvaluation>& candidates,
                              const ChoiceRule& rule);

}  // namespace avk::kinematics
