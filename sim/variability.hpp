#pragma once
// Repeats one turn under MOOS-like asynchronous timing (seeded random phases and tick jitter) to
// show how much a simulated turn varies (thesis §5.1, Figures 5-1 and 5-2).

#include <cstdint>
#include <vector>

#include "kinematics/ckt.hpp"
#include "sim/turn_scenario.hpp"

namespace avk::sim {

struct VariabilityConfig {
  TurnScenarioConfig base{};
  int repeats = 77;
  bool jitter = true;  // random phases + per-tick jitter; false: every run identical
  double jitter_fraction = 0.05;
  std::uint64_t first_seed = 1;
};

struct VariabilityRow {
  int repetition = 0;
  std::uint64_t seed = 0;
  bool completed = false;
  double advance_m = 0.0;
  double transfer_m = 0.0;
};

struct VariabilityResult {
  std::vector<VariabilityRow> rows;
  kinematics::MeanSd advance_m;
  kinematics::MeanSd transfer_m;
  double advance_cv = 0.0;  // sd / mean
  double transfer_cv = 0.0;
  int distinct_outcomes = 0;  // distinct (advance, transfer) at 1 cm resolution: the clusters
};

VariabilityResult run_variability(const VariabilityConfig& config);

}  // namespace avk::sim
