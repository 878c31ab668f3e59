#pragma once
// The kinds of vehicle the station can drive, simulated or real. A stored vehicle keeps the kind
// it was recorded with as text (VehicleInfo::kind, which may also name a vehicle known only from
// imported logs); everything that behaves differently by kind works on this enum, parsed once at
// the edge (a command-line option, a simulator config, a stored record).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avk::vehicle {

enum class VehicleKind {
  usim,             // the thesis' uSimMarine: one rudder and one thruster, exact navigation
  catamaran_m200,   // the simulated Kingfisher M200 (differential drive)
  catamaran_heron,  // the simulated Heron (differential drive)
  catamaran_otter,  // the simulated Otter (differential drive)
  m200,             // a real Kingfisher M200 over its frontseat link
};

// "usim", "catamaran:m200", "catamaran:heron", "catamaran:otter", "m200".
const char* to_string(VehicleKind k);
// The names to_string gives, and "catamaran" for catamaran:m200 (the default hull). nullopt for
// anything else.
std::optional<VehicleKind> vehicle_kind_from_string(std::string_view s);
// Every kind, in declaration order.
const std::vector<VehicleKind>& all_vehicle_kinds();
// The kinds the simulator drives (every kind but the real vehicles).
bool is_simulated(VehicleKind k);
// Differential-drive kinds: left and right thrusters, so they can stand behind a frontseat
// emulator that speaks $PYDIR.
bool has_differential_drive(VehicleKind k);
// A simulated differential-drive kind: what the frontseat emulator can stand for.
bool can_emulate_frontseat(VehicleKind k);
// "usim, catamaran, catamaran:m200, ..." of the kinds that pass `keep`: for messages that name
// what is accepted.
std::string vehicle_kind_names(bool (*keep)(VehicleKind) = nullptr);
// The kind parsed from s; std::invalid_argument naming s and the accepted kinds otherwise.
VehicleKind parse_vehicle_kind(std::string_view s);

}  // namespace avk::vehicle
