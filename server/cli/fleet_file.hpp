#pragma once
// `avk serve --vehicles FILE`: the station's fleet as a document. Each vehicle is simulated (its
// kind, sim config file, seed and start pose) or an M200 by its frontseat address:
//
//   {"vehicles": [
//     {"id": "alpha", "vehicle": "catamaran:m200", "sim_config": "sim-choppy.json", "seed": 1,
//      "start": {"x_m": 0, "y_m": 0, "heading_deg": 90}},
//     {"id": "lab-boat", "m200": "192.168.1.20:29500", "pid": "m200_in_water"}]}
//
// A sim config path is relative to the fleet file's folder, so a fleet and its configs move
// together.

#include <optional>
#include <string>
#include <vector>

#include "app/vehicle_loop.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::server {

// The vehicles of the document at `path` (its text given), with the station clock and pace of
// this run. Throws std::runtime_error naming the file and the JSON pointer of what is wrong.
std::vector<app::VehicleLoopOptions> parse_fleet_file(const std::string& path,
                                                      const std::string& text,
                                                      double realtime_factor, double start_clock_s,
                                                      const std::optional<vehicle::LatLon>& datum);

}  // namespace avk::server
