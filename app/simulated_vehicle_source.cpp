// The simulator's vehicles (every simulated kind) as a vehicle source.

#include <stdexcept>

#include "app/vehicle_source_maker.hpp"
#include "sim/sim_mission.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::app {

namespace {

class SimulatedSource final : public VehicleSource {
 public:
  SimulatedSource(const VehicleSourceOptions& o, sim::Scheduler& scheduler)
      : vehicle_(sim::vehicle_at_rest(o.setup, o.start), scheduler),
        realtime_(o.realtime),
        factor_(o.realtime_factor) {}

  vehicle::Vehicle& vehicle() override { return vehicle_; }
  std::unique_ptr<sim::Pacer> pacer() override {
    if (realtime_) return std::make_unique<sim::RealtimePacer>(factor_);
    return std::make_unique<sim::FastPacer>();
  }

 private:
  sim::SimVehicle vehicle_;
  bool realtime_;
  double factor_;
};

vehicle::VehicleInfo planned_info(const VehicleSourceOptions& o) {
  return {o.setup.vehicle.id, vehicle::to_string(o.setup.vehicle.kind),
          o.setup.vehicle_max_speed_mps(),
          o.setup.vehicle.catamaran ? std::optional(o.setup.vehicle.catamaran->length_m)
                                    : std::nullopt};
}

std::unique_ptr<VehicleSource> make(const VehicleSourceOptions& o, sim::Scheduler& scheduler) {
  if (o.setup.vehicle.kind != kind_of(o)) {
    throw std::invalid_argument(std::string("the simulator setup is for a ") +
                                vehicle::to_string(o.setup.vehicle.kind) + ", not a " +
                                vehicle::to_string(kind_of(o)));
  }
  return std::make_unique<SimulatedSource>(o, scheduler);
}

}  // namespace

VehicleSourceMaker simulated_vehicle_source() {
  return {planned_info, make};
}

}  // namespace avk::app
