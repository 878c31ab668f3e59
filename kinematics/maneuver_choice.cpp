#include "kinematics/maneuver_choice.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace avk::kinematics {

namespace {

// a is preferred to b: smaller |Δψ|, then starboard.
bool smaller_turn(const CandidateEvaluation& a, const CandidateEvaluation& b) {
  const double aa = std::abs(a.dheading_deg), ab = std::abs(b.dheading_deg);
  if (aa < ab - 1e-9) return true;
  return std::abs(aa - ab) <= 1e-9 && a.dheading_deg > b.dheading_deg;
}

std::optional<std::size_t> smallest_within(const std::vector<CandidateEvaluation>& cs,
                                           double max_risk, bool starboard_only) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    if (cs[i].risk > max_risk) continue;
    if (starboard_only && cs[i].dheading_deg < 0.0) continue;
    if (!best || smaller_turn(cs[i], cs[*best])) best = i;
  }
  return best;
}

std::string percent(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g %%", share * 100.0);
  return buf;
}

}  // namespace

ManeuverChoice choose_by_risk(const ManeuverProblem& problem, double own_speed_mps,
                              const std::vector<CandidateEvaluation>& candidates,
                              const ChoiceRule& rule) {
  if (!(rule.max_risk >= 0.0 && rule.max_risk <= 1.0))
    throw std::invalid_argument("the risk limit must be within [0, 1]");
  ManeuverChoice out;
  if (candidates.empty()) {
    out.explanation = "no candidates";
    return out;
  }
  const std::string limit = percent(rule.max_risk);
  bool starboard = false;
  if (rule.prefer_starboard) {
    // The contacts that matter are those the held course would bring inside the standoff.
    const CandidateEvaluation* held = nullptr;
    for (const auto& c : candidates)
      if (c.dheading_deg == 0.0) held = &c;
    for (std::size_t k = 0; k < problem.contacts.size(); ++k) {
      const bool endangered = !held || held->contacts.size() != problem.contacts.size() ||
                              held->contacts[k].risk > rule.max_risk;
      if (!endangered) continue;
      const Situation s = classify_encounter(problem.own, own_speed_mps, problem.contacts[k]);
      out.situations.push_back(s);
      if (asks_starboard(s)) {
        starboard = true;
        if (out.colregs_rule.empty() || s == Situation::head_on) out.colregs_rule = rule_of(s);
      }
    }
  }
  std::optional<std::size_t> pick;
  if (starboard) {
    pick = smallest_within(candidates, rule.max_risk, true);
    if (pick) {
      out.explanation = "rule " + out.colregs_rule +
                        ": the smallest starboard turn (or the held course) with risk <= " + limit;
    } else {
      out.explanation = "rule " + out.colregs_rule + " asks for starboard, but no starboard turn " +
                        "has risk <= " + limit + "; the smallest turn either side that has";
      out.colregs_rule.clear();
    }
  }
  if (!pick) {
    pick = smallest_within(candidates, rule.max_risk, false);
    if (pick && out.explanation.empty())
      out.explanation = "the smallest heading change with risk <= " + limit;
  }
  if (!pick) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      const double a = candidates[i].risk, b = candidates[best].risk;
      if (a < b - 1e-12 ||
          (std::abs(a - b) <= 1e-12 && smaller_turn(candidates[i], candidates[best])))
        best = i;
    }
    pick = best;
    out.colregs_rule.clear();
    out.explanation = "no candidate has risk <= " + limit + ": the least risky one";
  }
  out.index = pick;
  const CandidateEvaluation& c = candidates[*pick];
  out.risk = c.risk;
  out.within_limit = c.risk <= rule.max_risk;
  out.margin_m = c.min_cpa_m - problem.standoff_m;
  return out;
}

}  // namespace avk::kinematics
