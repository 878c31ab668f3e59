#pragma once
// The simulator configuration file (docs/sim-config.md): vehicle kind, tick rates, controller
// gains, disturbances and sensor noise, over the defaults of the vehicle kind.

#include <string>
#include <string_view>

#include "sim/scheduler.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::sim {

struct SimSetup {
  SimVehicleConfig vehicle = sim_vehicle_defaults(vehicle::VehicleKind::usim);
  SchedulerOptions scheduler{};
  double helm_hz = 4.0;  // pHelmIvP / mission AppTick
  double vehicle_max_speed_mps() const;
};

// Defaults of a simulated vehicle kind (given as text: vehicle_kind_from_string); throws
// std::invalid_argument naming an unknown kind or one the simulator does not drive.
SimSetup default_sim_setup(vehicle::VehicleKind kind);
SimSetup default_sim_setup(std::string_view kind);

// Reads a sim config document over the defaults of its "vehicle" (or of default_kind). Throws
// kinematics::ParseError naming the JSON pointer of the bad field; unknown fields are errors.
SimSetup parse_sim_config(std::string_view json_text, const std::string& default_kind);

}  // namespace avk::sim
