#pragma once
// How a vehicle kind's source is made: what each kind's file (simulated_vehicle_source.cpp,
// m200_vehicle_source.cpp, ...) gives vehicle_sources.cpp's registration table.

#include <memory>

#include "app/vehicle_source.hpp"

namespace avk::app {

struct VehicleSourceMaker {
  vehicle::VehicleInfo (*planned_info)(const VehicleSourceOptions&);
  std::unique_ptr<VehicleSource> (*make)(const VehicleSourceOptions&, sim::Scheduler&);
};

}  // namespace avk::app
