#pragma once
// The cells a CKT answer blends, with their weights: what the table's query and its materialised
// fine grid hand to blend_corridors and blend_timings.

#include <optional>
#include <utility>
#include <vector>

#include "kinematics/corridor.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

using CorridorSources = std::vector<std::pair<const std::optional<Corridor>*, double>>;
using TimingSources = std::vector<std::pair<const std::optional<TurnTiming>*, double>>;

}  // namespace avk::kinematics
