#pragma once
// The vehicles the station knows: those it drives now (live, its fleet), and those of stored
// missions.

#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "app/vehicle_snapshot.hpp"

namespace avk::app {

class Context;

struct VehicleStatus {
  vehicle::VehicleInfo info;
  // A vehicle of the station's fleet: its live state. None for a vehicle known only from the
  // store (its link is disconnected).
  std::optional<VehicleSnapshot> live;
};

// The station's fleet first, in its order, then every other vehicle of a stored mission.
std::vector<VehicleStatus> list_vehicles(Context& ctx);
Result<VehicleStatus> get_vehicle(Context& ctx, const std::string& vehicle_id);

}  // namespace avk::app
