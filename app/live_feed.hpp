#pragma once
// Where the station's vehicle loop tells what happens live (the stream's nav, helm, mission,
// turn and status topics), as domain values: the server turns them into the stream's JSON, a
// test or the command line can ignore them.

#include <cstdint>
#include <memory>
#include <string>

#include "app/current_view.hpp"
#include "app/vehicle_snapshot.hpp"
#include "mission/event_kind.hpp"
#include "mission/mission_observer.hpp"
#include "mission/mission_runner.hpp"

namespace avk::app {

class LiveFeed {
 public:
  virtual ~LiveFeed() = default;
  // The vehicle at the telemetry rate: navigation (when it has any) and the helm.
  virtual void telemetry(const VehicleSnapshot& s) = 0;
  // A station event an operator reads (a mission attached, detached).
  virtual void station_event(double t_s, mission::EventKind kind, const std::string& message) = 0;
  // Follows a mission the loop starts: turns, progress, events. Kept by the loop while it runs.
  virtual std::unique_ptr<mission::MissionObserver> follow(
      std::int64_t mission_id, const mission::MissionRunner& runner) = 0;
  // A new estimate of the current the running mission is in (app/current_tracker.hpp).
  virtual void current(const std::string& /*vehicle_id*/, const CurrentView& /*c*/) {}
};

// Tells nobody: for the command line and for tests that do not watch the stream.
class SilentFeed final : public LiveFeed {
 public:
  void telemetry(const VehicleSnapshot&) override {}
  void station_event(double, mission::EventKind, const std::string&) override {}
  std::unique_ptr<mission::MissionObserver> follow(std::int64_t,
                                                   const mission::MissionRunner&) override {
    return std::make_unique<mission::MissionObserver>();
  }
};

}  // namespace avk::app
