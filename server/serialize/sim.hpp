#pragma once
// The simulator's runs as documents (`avk sim`): one turn's navigation, the spread of repeated
// turns, and that spread over the plant's and the helm's tick rate.

#include <string>
#include <vector>

#include "sim/turn_scenario.hpp"
#include "sim/variability.hpp"

namespace avk::server {

// Every navigation sample of the run with what the helm asked and the actuators gave.
std::string sim_turn_csv(const sim::TurnScenarioResult& r);
// A row per repetition, then the spread as one `#` comment line.
std::string variability_csv(const sim::VariabilityResult& v);
// One repeated turn at one tick rate of the plant and the helm together.
struct TickSweepRow {
  int tick_hz = 0;
  int repeats = 0;
  sim::VariabilityResult result;
};
std::string tick_sweep_csv(const std::vector<TickSweepRow>& rows);

}  // namespace avk::server
