#include <map>
#include <stdexcept>

#include "app/vehicle_source_maker.hpp"

namespace avk::app {

// Each kind's source lives in its own file; it is known to the station by its line here.
VehicleSourceMaker simulated_vehicle_source();  // simulated_vehicle_source.cpp
VehicleSourceMaker m200_vehicle_source();       // m200_vehicle_source.cpp

namespace {

const VehicleSourceMaker& maker_for(vehicle::VehicleKind kind) {
  static const std::map<vehicle::VehicleKind, VehicleSourceMaker> makers = {
      {vehicle::VehicleKind::usim, simulated_vehicle_source()},
      {vehicle::VehicleKind::catamaran_m200, simulated_vehicle_source()},
      {vehicle::VehicleKind::catamaran_heron, simulated_vehicle_source()},
      {vehicle::VehicleKind::catamaran_otter, simulated_vehicle_source()},
      {vehicle::VehicleKind::m200, m200_vehicle_source()},
  };
  const auto it = makers.find(kind);
  if (it == makers.end()) {
    throw std::invalid_argument(std::string("no vehicle source for kind ") +
                                vehicle::to_string(kind));
  }
  return it->second;
}

}  // namespace

vehicle::VehicleKind kind_of(const VehicleSourceOptions& options) {
  return options.kind.value_or(options.setup.vehicle.kind);
}

sim::SchedulerOptions scheduler_options(const VehicleSourceOptions& options) {
  sim::SchedulerOptions s = options.setup.scheduler;
  s.start_time_s = options.start_clock_s;
  return s;
}

vehicle::VehicleInfo planned_vehicle_info(const VehicleSourceOptions& options) {
  return maker_for(kind_of(options)).planned_info(options);
}

std::unique_ptr<VehicleSource> make_vehicle_source(const VehicleSourceOptions& options,
                                                   sim::Scheduler& scheduler) {
  return maker_for(kind_of(options)).make(options, scheduler);
}

}  // namespace avk::app
