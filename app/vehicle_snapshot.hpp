#pragma once
// The station's vehicle as a moment's picture, and a running mission's live progress.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mission/helm_mode.hpp"
#include "mission/mission_runner.hpp"
#include "mission/vehicle_command.hpp"
#include "vehicle/m200.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

// What the vehicle's helm runs when no mission drives it: the operator's command (hold, go to,
// return, stop) or the hold at the last mission's return point, with its point once known.
struct VehicleCommandState {
  mission::VehicleCommand command;
  std::optional<double> distance_m;  // from the point, at the last helm tick
};

struct VehicleSnapshot {
  vehicle::VehicleInfo info;
  vehicle::LinkState link = vehicle::LinkState::disconnected;
  std::optional<vehicle::NavSample> nav;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  // None: neither a mission nor a command drives the helm (the vehicle is at all stop).
  std::optional<mission::HelmMode> helm_mode;
  std::optional<std::int64_t> mission_id;
  std::optional<VehicleCommandState> command;  // set while no mission runs
  double t_s = 0.0;
  // A real vehicle's frontseat: link counters and battery.
  std::optional<vehicle::M200Status> frontseat;
};

struct MissionLive {
  std::int64_t mission_id = 0;
  std::optional<mission::MissionState> state;  // none: attached, not started yet
  mission::HelmMode helm_mode{};
  std::vector<mission::CellProgress> cells;
  std::optional<mission::RunningTurn> turn;  // the turn under way
};

}  // namespace avk::app
