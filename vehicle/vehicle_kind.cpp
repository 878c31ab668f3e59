#include "vehicle/vehicle_kind.hpp"

#include <stdexcept>

namespace avk::vehicle {

const char* to_string(VehicleKind k) {
  switch (k) {
    case VehicleKind::usim:
      return "usim";
    case VehicleKind::catamaran_m200:
      return "catamaran:m200";
    case VehicleKind::catamaran_heron:
      return "catamaran:heron";
    case VehicleKind::catamaran_otter:
      return "catamaran:otter";
    case VehicleKind::m200:
      return "m200";
  }
  return "?";
}

const std::vector<VehicleKind>& all_vehicle_kinds() {
  // to_string's switch is checked to name every enumerator (0..n-1), and answers "?" past them.
  static const std::vector<VehicleKind> all = [] {
    std::vector<VehicleKind> out;
    for (int i = 0; std::string_view(to_string(static_cast<VehicleKind>(i))) != "?"; ++i)
      out.push_back(static_cast<VehicleKind>(i));
    return out;
  }();
  return all;
}

std::optional<VehicleKind> vehicle_kind_from_string(std::string_view s) {
  if (s == "catamaran") return VehicleKind::catamaran_m200;
  for (const VehicleKind k : all_vehicle_kinds())
    if (s == to_string(k)) return k;
  return std::nullopt;
}

bool is_simulated(VehicleKind k) {
  return k != VehicleKind::m200;
}

bool has_differential_drive(VehicleKind k) {
  return k != VehicleKind::usim;
}

bool can_emulate_frontseat(VehicleKind k) {
  return is_simulated(k) && has_differential_drive(k);
}

std::string vehicle_kind_names(bool (*keep)(VehicleKind)) {
  std::string out;
  const auto add = [&out](std::string_view name) {
    if (!out.empty()) out += ", ";
    out += name;
  };
  for (const VehicleKind k : all_vehicle_kinds()) {
    if (keep && !keep(k)) continue;
    if (k == VehicleKind::catamaran_m200) add("catamaran");
    add(to_string(k));
  }
  return out;
}

VehicleKind parse_vehicle_kind(std::string_view s) {
  if (const auto k = vehicle_kind_from_string(s)) return *k;
  throw std::invalid_argument("unknown vehicle kind '" + std::string(s) + "' (" +
                              vehicle_kind_names() + ")");
}

}  // namespace avk::vehicle
