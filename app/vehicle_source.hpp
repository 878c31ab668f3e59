#pragma once
// Where a mission's vehicle comes from: a simulated kind stepped by the caller's scheduler, or a
// real vehicle over its link, each behind vehicle::Vehicle. One source per kind, made by
// make_vehicle_source from the registration table in vehicle_sources.cpp: a new kind is its
// source file and one line there; the mission, the station's vehicle loop and the front ends
// only ever see this interface.

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "kinematics/geometry.hpp"
#include "sim/scheduler.hpp"
#include "sim/sim_config.hpp"
#include "vehicle/m200.hpp"
#include "vehicle/scaled_clock.hpp"
#include "vehicle/vehicle.hpp"
#include "vehicle/vehicle_kind.hpp"

namespace avk::app {

struct VehicleSourceOptions {
  // None: the simulator setup's kind.
  std::optional<vehicle::VehicleKind> kind;
  // Simulated kinds: the vehicle (its kind, id and plant); every kind: the helm rate.
  sim::SimSetup setup;
  // A real M200: its link and frontseat settings (the vehicle id is config.id).
  std::optional<vehicle::M200Options> m200;
  kinematics::Pose start{};    // a simulated vehicle starts here, at rest
  double start_clock_s = 0.0;  // a real vehicle's clock starts here (the scheduler's, for both)
  // A real vehicle's clock runs at the wall clock x this; a simulated one is paced to it when
  // realtime, and runs as fast as it can otherwise.
  double realtime_factor = 1.0;
  bool realtime = true;
};

// The kind the options ask for.
vehicle::VehicleKind kind_of(const VehicleSourceOptions& options);

class VehicleSource {
 public:
  virtual ~VehicleSource() = default;

  virtual vehicle::Vehicle& vehicle() = 0;
  // How the scheduler the source was made with is paced: a simulated vehicle's time is the
  // scheduler's own; a real vehicle's is its clock.
  virtual std::unique_ptr<sim::Pacer> pacer() = 0;
  // A real vehicle moves by itself on this clock: a mission run to its end ticks its helm on it
  // (mission::run_helm_loop), not on a simulation schedule. None for simulated vehicles.
  virtual const vehicle::ScaledClock* wall_clock() const { return nullptr; }
  // Link counters and battery of a real vehicle's frontseat.
  virtual std::optional<vehicle::M200Status> frontseat_status() const { return std::nullopt; }
  // What the station connects to, for an operator ("the M200 frontseat at host:port"); empty
  // for a simulation.
  virtual std::string link_name() const { return {}; }
  // Blocks until navigation has arrived; the reason when it did not within the timeout.
  virtual std::optional<std::string> wait_for_nav(std::chrono::milliseconds) {
    return std::nullopt;
  }
  // After the last helm tick: the vehicle left stopped by the station's own command (a real
  // vehicle: before its link closes, not by its frontseat's watchdog).
  virtual void park() {}
  // Lines that describe the run's link afterwards (counters, battery); none for a simulation.
  virtual std::string link_report() const { return {}; }
};

// The scheduler a source is made with: the setup's (seed, jitter) with its clock at
// start_clock_s.
sim::SchedulerOptions scheduler_options(const VehicleSourceOptions& options);

// What the vehicle will report as itself, known before it is made or connected (so a mission
// file can be checked against its top speed without a vehicle).
vehicle::VehicleInfo planned_vehicle_info(const VehicleSourceOptions& options);

// The source for options.kind; a simulated vehicle registers its components with the scheduler,
// which must outlive the source. Throws std::invalid_argument for a kind without a source or
// options it needs (a real M200 without its link).
std::unique_ptr<VehicleSource> make_vehicle_source(const VehicleSourceOptions& options,
                                                   sim::Scheduler& scheduler);

}  // namespace avk::app
