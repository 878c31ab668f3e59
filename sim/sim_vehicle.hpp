#pragma once
// A simulated vehicle behind the Vehicle interface: plant + navigation sensor + the backseat
// controller (pMarinePID, and thrust mixing for differential drive), each a scheduler component
// that sees the others only through published values, as MOOS apps do.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sim/catamaran.hpp"
#include "sim/environment.hpp"
#include "sim/scheduler.hpp"
#include "sim/sensors.hpp"
#include "sim/usim.hpp"
#include "vehicle/marine_pid.hpp"
#include "vehicle/thrust_mixing.hpp"
#include "vehicle/vehicle.hpp"
#include "vehicle/vehicle_kind.hpp"

namespace avk::sim {

struct SimVehicleConfig {
  std::string id = "sim-1";
  vehicle::VehicleKind kind = vehicle::VehicleKind::usim;  // a simulated kind
  UsimConfig usim{};
  std::optional<CatamaranParams> catamaran;  // filled from kind when empty
  EnvironmentConfig environment{};
  SensorConfig sensors{};
  vehicle::MarinePidConfig pid = vehicle::MarinePidConfig::thesis_sim();
  vehicle::MixConfig mix{};
  double plant_hz = 4.0;       // uSimMarine AppTick; for the catamaran: navigation publication rate
  double controller_hz = 4.0;  // pMarinePID AppTick
  double stale_limit_s = 2.0;
  double start_x_m = 0.0;
  double start_y_m = 0.0;
  double start_heading_deg = 0.0;
  double start_speed_mps = 0.0;
  std::uint64_t seed = 1;
};

// Defaults for a kind: the thesis' uSimMarine (turn rate 30, exact navigation at the plant tick)
// or a catamaran with GNSS/compass noise published at 10 Hz. The M200 gets the thesis' in-water
// controller (Table 3.1, MarinePidConfig::m200_in_water), every other kind the simulation one
// (Table 5.1). Throws std::invalid_argument for a kind the simulator does not drive, naming it.
SimVehicleConfig sim_vehicle_defaults(vehicle::VehicleKind kind);
// The same for a kind given as text (vehicle_kind_from_string); std::invalid_argument naming an
// unknown one and the accepted kinds.
SimVehicleConfig sim_vehicle_defaults(std::string_view kind);

// The config with the catamaran parameters of its kind filled in when absent; usim configs
// unchanged.
SimVehicleConfig with_kind_defaults(SimVehicleConfig config);

// A catamaran config's plant at its start pose and its navigation sensor, seeded from
// config.seed exactly as a SimVehicle seeds them (so the frontseat emulator with the same seed
// sees the same gusts and noise). The config must have its catamaran parameters.
CatamaranPlant make_catamaran_plant(const SimVehicleConfig& config);
NavSensor make_nav_sensor(const SimVehicleConfig& config);

// The top operating speed: the catamaran's rating, or uSimMarine's full thrust over its thrust
// factor (or the end of its thrust map).
double max_speed_mps(const SimVehicleConfig& config);

class SimVehicle final : public vehicle::Vehicle {
 public:
  // Registers the plant and controller components with the scheduler (which must outlive this).
  SimVehicle(SimVehicleConfig config, Scheduler& scheduler);

  const vehicle::VehicleInfo& info() const override { return info_; }
  std::vector<vehicle::NavSample> take_nav() override;
  std::optional<vehicle::NavSample> last_nav() const override { return last_nav_; }
  vehicle::LinkState link_state(double now_s) const override;
  void command(const vehicle::DesiredCommand& desired) override;
  void all_stop(double now_s) override;
  std::optional<vehicle::DesiredCommand> last_command() const override { return desired_; }
  std::optional<vehicle::ActuatorCommand> last_actuators() const override { return actuators_; }

  // Ground truth, for tests and for logging what the sensors did not see.
  TruthSample truth() const;
  const SimVehicleConfig& config() const { return config_; }

  // Test hook: a navigation outage (nothing is delivered while cut).
  void set_nav_outage(bool cut) { nav_cut_ = cut; }

 private:
  void plant_tick(double now_s);
  void controller_tick(double now_s);

  SimVehicleConfig config_;
  vehicle::VehicleInfo info_;
  std::variant<UsimPlant, CatamaranPlant> plant_;
  NavSensor sensor_;
  vehicle::MarinePid pid_;
  std::optional<double> last_plant_time_s_;
  std::vector<vehicle::NavSample> mailbox_;     // delivered, not yet taken
  std::optional<vehicle::NavSample> last_nav_;  // newest delivered
  std::optional<vehicle::DesiredCommand> desired_;
  vehicle::ActuatorCommand actuators_{};  // published by the controller, read by the plant
  bool stopped_ = false;
  bool nav_cut_ = false;
};

}  // namespace avk::sim
