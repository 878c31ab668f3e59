#pragma once
// Commands that keep the station's vehicle safe when no mission drives it: hold a point (or
// where it is), go to a point and hold there, return to the last mission's return point (or a
// given one) and hold, all stop. Each is checked here, queued to the vehicle loop and applied at
// its next helm tick; a mission running on the vehicle is aborted first. Per vehicle: the
// vehicle id names which one.

#include <optional>
#include <string>

#include "app/result.hpp"
#include "app/vehicles.hpp"
#include "mission/vehicle_command.hpp"

namespace avk::app {

class Context;

// A commanded point is at most this far from the datum on either axis: the local grid is a flat
// approximation, and a typo of a few digits must not send a boat to sea.
inline constexpr double kMaxCommandCoordinateM = 100000.0;

struct VehicleCommandRequest {
  mission::VehicleCommandKind kind = mission::VehicleCommandKind::stop;
  std::optional<double> x_m;  // x_m and y_m together, or neither
  std::optional<double> y_m;
  std::optional<double> radius_m;   // none: mission::kDefaultHoldRadiusM
  std::optional<double> speed_mps;  // none: the helm's default transit speed
};

// The vehicle's status after the command took effect. invalid_argument naming the field
// (x_m, y_m, radius_m, speed_mps): a coordinate not finite or out of range, one coordinate
// without the other, go_to without a point, a radius not in (0, kMaxHoldRadiusM], a speed not in
// (0, the vehicle's top speed]. not_found for an unknown vehicle, conflict for one this station
// does not drive or a return with no point when no mission has run.
Result<VehicleStatus> command_vehicle(Context& ctx, const std::string& vehicle_id,
                                      const VehicleCommandRequest& request);

}  // namespace avk::app
