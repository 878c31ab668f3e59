#include "mission/command_helm.hpp"

#include <algorithm>

namespace avk::mission {

namespace {
constexpr double kMaxDefaultTransitMps = 1.5;
constexpr double kMaxDefaultHoldMps = 1.5;
constexpr double kDefaultTransitFraction = 0.8;
}  // namespace

StationKeepConfig default_station_keep(double max_speed_mps, double radius_m) {
  StationKeepConfig c;
  c.radius_m = radius_m;
  c.transit_speed_mps =
      max_speed_mps > 0.0 ? std::min(kMaxDefaultTransitMps, kDefaultTransitFraction * max_speed_mps)
                          : kMaxDefaultTransitMps;
  c.hold_speed_mps = std::min(kMaxDefaultHoldMps, c.transit_speed_mps);
  return c;
}

CommandHelm::CommandHelm(vehicle::Vehicle& vehicle) : vehicle_(vehicle) {}

void CommandHelm::command(const VehicleCommand& c, double) {
  active_ = c;
  keeper_.reset();
  stopped_ = false;
  arrival_reported_ = false;
  desired_heading_deg_.reset();
  desired_speed_mps_.reset();
  if (c.kind == VehicleCommandKind::return_to && !c.point) active_->point = return_point_;
  if (c.kind == VehicleCommandKind::stop) {
    active_->point.reset();
    return;
  }
  if (!active_->point) {
    if (const auto nav = vehicle_.last_nav())
      active_->point = kinematics::Point{nav->x_m, nav->y_m};
  }
  if (active_->point) start_keeping(*active_->point);
}

void CommandHelm::start_keeping(kinematics::Point p) {
  StationKeepConfig k = default_station_keep(vehicle_.info().max_speed_mps, active_->radius_m);
  if (active_->speed_mps) k.transit_speed_mps = *active_->speed_mps;
  k.hold_speed_mps = std::min(k.hold_speed_mps, k.transit_speed_mps);
  keeper_.emplace(p, k);
}

void CommandHelm::mission_started(const MissionConfig& config) {
  return_point_ = config.region.return_point;
}

bool CommandHelm::mission_ended(const MissionConfig& config, MissionState state, double now_s) {
  return_point_ = config.region.return_point;
  if (state != MissionState::done && state != MissionState::aborted &&
      state != MissionState::halted)
    return false;
  VehicleCommand hold;
  hold.kind = VehicleCommandKind::return_to;
  hold.point = config.region.return_point;
  // The capture radius is a few metres: the hold is held to the default radius, not to it.
  hold.radius_m = std::max(kDefaultHoldRadiusM, config.region.capture_radius_m);
  hold.speed_mps = return_speed_mps(config);
  command(hold, now_s);
  return true;
}

std::optional<HelmMode> CommandHelm::mode() const {
  if (!active_) return std::nullopt;
  if (active_->kind == VehicleCommandKind::stop) return HelmMode::stopped;
  return keeper_ && keeper_->arrived() ? HelmMode::holding : HelmMode::transiting;
}

bool CommandHelm::take_arrival() {
  if (!keeper_ || !keeper_->arrived() || arrival_reported_) return false;
  arrival_reported_ = true;
  return true;
}

void CommandHelm::tick(double now_s) {
  std::optional<vehicle::NavSample> nav;
  for (const vehicle::NavSample& s : vehicle_.take_nav())
    nav = s;
  if (!active_) return;
  const bool live = vehicle_.link_state(now_s) == vehicle::LinkState::live;
  if (!nav) nav = vehicle_.last_nav();
  if (active_->kind != VehicleCommandKind::stop && live && nav && !keeper_) {
    active_->point = kinematics::Point{nav->x_m, nav->y_m};  // held here: now it is known
    start_keeping(*active_->point);
  }
  if (active_->kind == VehicleCommandKind::stop || !live || !nav) {
    // All stop, and without navigation nothing can be held: stop and wait for it.
    desired_speed_mps_ = 0.0;
    if (!stopped_) vehicle_.all_stop(now_s);
    stopped_ = true;
    return;
  }
  stopped_ = false;
  const HelmOutput out = keeper_->update(*nav);
  desired_heading_deg_ = out.heading_deg;
  desired_speed_mps_ = out.speed_mps;
  vehicle_.command({now_s, out.heading_deg, out.speed_mps});
}

}  // namespace avk::mission
