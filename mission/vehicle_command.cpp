#include "mission/vehicle_command.hpp"

#include <array>

#include "kinematics/number_text.hpp"

namespace avk::mission {

namespace {
constexpr std::array<const char*, 4> kNames = {"hold", "go_to", "return", "stop"};
}

const char* to_string(VehicleCommandKind k) {
  return kNames[static_cast<std::size_t>(k)];
}

std::optional<VehicleCommandKind> vehicle_command_kind_from_string(std::string_view s) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (s == kNames[i]) return static_cast<VehicleCommandKind>(i);
  return std::nullopt;
}

std::string describe(const VehicleCommand& c) {
  using kinematics::fixed_text;
  if (c.kind == VehicleCommandKind::stop) return "all stop";
  std::string out = to_string(c.kind);
  if (c.point) {
    out += (c.kind == VehicleCommandKind::go_to ? " (" : " at (") + fixed_text(c.point->x_m, 1) +
           ", " + fixed_text(c.point->y_m, 1) + ")";
  } else {
    out += c.kind == VehicleCommandKind::hold ? " here" : " to the last mission's return point";
  }
  if (c.speed_mps) out += " at " + fixed_text(*c.speed_mps, 2) + " m/s";
  return out + ", holding within " + fixed_text(c.radius_m, 1) + " m";
}

}  // namespace avk::mission
