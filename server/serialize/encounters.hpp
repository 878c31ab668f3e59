#pragma once
// The encounter test bench's run as documents (`avk encounter run`): every scenario with what
// each prediction method chose and what the flight showed, and the methods' summary.

#include <nlohmann/json.hpp>
#include <string>

#include "app/encounters.hpp"

namespace avk::server {

// The run with the question it answered (vehicle, plant, seeds, rule) and the current it assumed.
nlohmann::json encounter_bench_json(const app::EncounterBench& b,
                                    const app::EncounterBenchQuery& q);
// A row per scenario and method; flags as 1 or 0.
std::string encounter_bench_csv(const app::EncounterBench& b);

}  // namespace avk::server
