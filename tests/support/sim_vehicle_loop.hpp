#pragma once
// The station's vehicle loop driving the simulated usim "sim-usim", at rest at the return point
// of the tests' missions (0, -70) facing north, on a clock `realtime_factor` times the wall's.

#include "app/vehicle_loop.hpp"
#include "sim/sim_config.hpp"

namespace avk::testing {

inline app::VehicleLoopOptions sim_usim_loop_options(double realtime_factor,
                                                     double telemetry_hz = 10.0) {
  app::VehicleLoopOptions v;
  v.setup = sim::default_sim_setup("usim");
  v.setup.vehicle.id = "sim-usim";
  v.realtime_factor = realtime_factor;
  v.telemetry_hz = telemetry_hz;
  v.start = {0.0, -70.0, 0.0};
  return v;
}

}  // namespace avk::testing
