#pragma once
// How the mission runner names a cell and a position in the events an operator reads.

#include <string>

#include "mission/turn_plan.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

// "1.50 m/s, 90 deg", or "1.50 -> 2.00 m/s, 90 deg" for a speed-change cell.
std::string cell_name(const TurnTask& t);

// "(12.3, -4.5) m" in the local grid.
std::string position_text(const vehicle::NavSample& s);

}  // namespace avk::mission
