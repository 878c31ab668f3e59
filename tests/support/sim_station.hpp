#pragma once
// The options of a station that drives the simulated usim "sim-usim", at rest at the return point
// of the tests' missions (0, -70) facing north, on a clock `realtime_factor` times the wall's.

#include <string>

#include "server/station.hpp"
#include "support/sim_vehicle_loop.hpp"

namespace avk::testing {

inline server::StationOptions sim_station_options(const std::string& db_path,
                                                  const std::string& token, double realtime_factor,
                                                  double telemetry_hz = 10.0) {
  server::StationOptions o;
  o.db_path = db_path;
  o.token = token;
  o.server_version = "test";
  o.vehicles.push_back(sim_usim_loop_options(realtime_factor, telemetry_hz));
  return o;
}

}  // namespace avk::testing
