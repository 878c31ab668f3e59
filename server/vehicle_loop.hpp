#pragma once
// The station's vehicle, always running (at rest under all stop when no mission runs): the
// simulator paced to the wall clock x a factor, or an M200 over its frontseat link on a clock at
// the same factor. Missions attach to it; the helm ticks the attached mission,
// a 10 Hz telemetry tick publishes nav and helm to the stream. Operator commands from other
// threads are queued and applied at the next helm tick, on the loop's own thread.

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mission/mission_runner.hpp"
#include "server/mission_plans.hpp"
#include "server/stream_hub.hpp"
#include "sim/sim_config.hpp"
#include "vehicle/m200.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::server {

struct VehicleSnapshot {
  vehicle::VehicleInfo info;
  vehicle::LinkState link = vehicle::LinkState::disconnected;
  std::optional<vehicle::NavSample> nav;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  std::string helm_mode = "IDLE";
  std::optional<std::int64_t> mission_id;
  double t_s = 0.0;
  std::optional<vehicle::M200Status> m200;  // link counters and battery of a real vehicle
};

// A real vehicle's frontseat link as the API and the live stream show it (docs/api.md):
// connected, failsafe, battery_v, sentences, bad_lines, last_error, pydir_sent, failsafe_stops,
// disconnects, last_link_error.
nlohmann::json frontseat_json(const vehicle::M200Status& s);

struct MissionLive {
  std::int64_t mission_id = 0;
  std::string state;  // running, paused, ...
  std::string helm_mode;
  std::vector<mission::CellProgress> cells;
  std::optional<double> condition_set_time_s;  // the last turn's
};

struct VehicleLoopOptions {
  sim::SimSetup setup;  // the simulated vehicle, and the helm rate for either kind
  // Set: the station drives an M200 over its frontseat link instead of simulating a vehicle.
  std::optional<vehicle::M200Options> m200;
  double realtime_factor = 1.0;
  double start_clock_s = 0.0;  // the station clock continues after everything stored
  kinematics::Pose start{};
  double telemetry_hz = 10.0;
};

class VehicleLoop {
 public:
  VehicleLoop(VehicleLoopOptions options, std::string db_path, StreamHub& hub);
  ~VehicleLoop();

  void start();
  // Interrupts an attached mission (stored as interrupted, resumable), flushes, joins.
  void stop(const std::string& reason = "the server stopped");

  const vehicle::VehicleInfo& info() const { return info_; }
  VehicleSnapshot snapshot() const;
  std::optional<MissionLive> live(std::int64_t mission_id) const;
  std::optional<std::int64_t> attached_mission() const;

  // Attaches a planned mission; false when another one is attached.
  bool attach(MissionPlan plan);
  enum class Command { pause, resume, abort };
  // Queues the command for the attached mission; false when that mission is not attached. The
  // result shows in live() after the next helm tick.
  bool command(std::int64_t mission_id, Command c);
  // Blocks until the loop has run a helm tick after this call (bounded by timeout); for callers
  // that want to read the effect of a command.
  bool wait_for_tick(std::chrono::milliseconds timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  vehicle::VehicleInfo info_;
};

}  // namespace avk::server
