#pragma once
// One vehicle of the station, always running (at rest under all stop when no mission runs): a
// vehicle source of any kind (the simulator paced to the wall clock x a factor, or a real vehicle
// over its link on a clock at the same factor). Missions attach to it; the helm ticks the attached
// mission, a 10 Hz telemetry tick tells the live feed where the vehicle is. Operator commands from
// other threads are queued and applied at the next helm tick, on the loop's own thread.

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/live_feed.hpp"
#include "app/mission_plans.hpp"
#include "app/vehicle_snapshot.hpp"
#include "app/vehicle_source.hpp"
#include "mission/mission_runner.hpp"
#include "mission/vehicle_command.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

// The vehicle (any kind with a source: the station clock continues after everything stored,
// in start_clock_s), always paced in real time x realtime_factor, and the telemetry rate.
struct VehicleLoopOptions : VehicleSourceOptions {
  double telemetry_hz = 10.0;
};

class VehicleLoop {
 public:
  VehicleLoop(VehicleLoopOptions options, std::string db_path, LiveFeed& feed);
  ~VehicleLoop();

  void start();
  // Asks the loop to stop without waiting for it: a fleet stops all its vehicles at once.
  void request_stop(const std::string& reason = "the server stopped");
  // Interrupts an attached mission (stored as interrupted, resumable), flushes, joins.
  void stop(const std::string& reason = "the server stopped");

  const vehicle::VehicleInfo& info() const { return info_; }
  // What the vehicle was made from (its kind, simulator setup, start pose, clock).
  const VehicleLoopOptions& options() const;
  VehicleSnapshot snapshot() const;
  std::optional<MissionLive> live(std::int64_t mission_id) const;
  std::optional<std::int64_t> attached_mission() const;

  // Attaches a planned mission; false when another one is attached.
  bool attach(MissionPlan plan);
  enum class Command { pause, resume, abort };
  // Queues the command for the attached mission; false when that mission is not attached. The
  // result shows in live() after the next helm tick.
  bool command(std::int64_t mission_id, Command c);
  // Queues a vehicle command (hold, go to, return, stop), applied at the next helm tick: an
  // attached mission is aborted first (its log says why), then the helm runs the command until
  // another command or a mission replaces it. False while the loop is stopping.
  bool command_vehicle(mission::VehicleCommand c);
  // Tells the vehicle's live feed a station event about it, from any thread (the collision
  // watch's alarms).
  void announce(double t_s, mission::EventKind kind, const std::string& message);
  // The return point of the last mission that ran on the vehicle (where `return` goes).
  std::optional<kinematics::Point> last_return_point() const;
  // Blocks until the loop has run a helm tick after this call (bounded by timeout); for callers
  // that want to read the effect of a command.
  bool wait_for_tick(std::chrono::milliseconds timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  vehicle::VehicleInfo info_;
};

}  // namespace avk::app
