#include "sim/variability.hpp"

#include <cmath>
#include <set>

#include "kinematics/turn_measures.hpp"

namespace avk::sim {

VariabilityResult run_variability(const VariabilityConfig& config) {
  VariabilityResult r;
  std::vector<double> advances, transfers;
  std::set<std::pair<long, long>> outcomes;
  for (int k = 0; k < config.repeats; ++k) {
    TurnScenarioConfig c = config.base;
    c.scheduler.seed = config.first_seed + static_cast<std::uint64_t>(k);
    c.scheduler.random_phases = config.jitter;
    c.scheduler.jitter_fraction = config.jitter ? config.jitter_fraction : 0.0;
    const TurnScenarioResult run = run_turn_scenario(c);
    VariabilityRow row{k + 1, c.scheduler.seed, run.completed, 0.0, 0.0};
    if (run.turn.samples().size() >= 2) {
      const auto at = kinematics::advance_transfer(run.turn);
      row.advance_m = at.advance_m;
      row.transfer_m = at.transfer_m;
      if (run.completed) {
        advances.push_back(at.advance_m);
        transfers.push_back(at.transfer_m);
        outcomes.insert({std::lround(at.advance_m * 100.0), std::lround(at.transfer_m * 100.0)});
      }
    }
    r.rows.push_back(row);
  }
  r.advance_m = kinematics::mean_sd(advances);
  r.transfer_m = kinematics::mean_sd(transfers);
  r.advance_cv = r.advance_m.mean != 0.0 ? r.advance_m.sd / r.advance_m.mean : 0.0;
  r.transfer_cv = r.transfer_m.mean != 0.0 ? r.transfer_m.sd / r.transfer_m.mean : 0.0;
  r.distinct_outcomes = static_cast<int>(outcomes.size());
  return r;
}

}  // namespace avk::sim
