#pragma once
// What an operator commands a vehicle to do when no mission drives it: hold a point, go to a
// point and hold there, return (to the last mission's return point) and hold, or all stop.
// Per vehicle: each vehicle's helm keeps its own.

#include <optional>
#include <string>
#include <string_view>

#include "kinematics/geometry.hpp"
#include "mission/station_keeping.hpp"

namespace avk::mission {

enum class VehicleCommandKind { hold, go_to, return_to, stop };
// "hold", "go_to", "return", "stop".
const char* to_string(VehicleCommandKind k);
std::optional<VehicleCommandKind> vehicle_command_kind_from_string(std::string_view s);

struct VehicleCommand {
  VehicleCommandKind kind = VehicleCommandKind::stop;
  // hold: none is where the vehicle is when the command applies; return: none is the last
  // mission's return point; go_to: always set.
  std::optional<kinematics::Point> point;
  double radius_m = kDefaultHoldRadiusM;
  std::optional<double> speed_mps;  // the transit speed; none: the helm's default
};

// "hold at (12.0, -3.5) within 5.0 m", for the event log.
std::string describe(const VehicleCommand& c);

}  // namespace avk::mission
