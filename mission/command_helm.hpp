#pragma once
// The helm of a vehicle no mission drives: it runs the operator's command (hold, go to, return,
// stop; mission/vehicle_command.hpp) and, when a mission ends, holds the vehicle at the mission's
// return point, so that a boat left alone does not drift away in the current. One per vehicle;
// whoever owns the clock calls tick() at the helm's AppTick while no mission is attached.

#include <optional>

#include "mission/helm_mode.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_observer.hpp"
#include "mission/station_keeping.hpp"
#include "mission/vehicle_command.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::mission {

// The speeds the helm uses when a command does not give one, for a vehicle of this top speed
// (0: unknown): transit at 80 % of it and no faster than 1.5 m/s, hold at up to the transit
// speed. Slower, the M200 in a 5 m/s wind answers its rudder too late to stay within 10 m.
StationKeepConfig default_station_keep(double max_speed_mps, double radius_m);

class CommandHelm {
 public:
  explicit CommandHelm(vehicle::Vehicle& vehicle);

  // Replaces the behaviour from now on. A hold without a point holds where the vehicle was last
  // seen (at the next navigation if it has none yet); a return without a point goes to the last
  // mission's return point (holds here when no mission has ended or started on this helm).
  void command(const VehicleCommand& c, double now_s);
  // A mission starts on this vehicle: its return point is the one `return` goes to.
  void mission_started(const MissionConfig& config);
  // A mission ended: done, aborted and halted hold at its return point at its return speed (true);
  // paused or interrupted change nothing (false).
  bool mission_ended(const MissionConfig& config, MissionState state, double now_s);
  // Forget the behaviour: the vehicle is left at all stop by whoever drives it next.
  void clear() { active_.reset(), keeper_.reset(); }

  void tick(double now_s);

  // None: no command since the start (or since clear()).
  std::optional<HelmMode> mode() const;
  // The command being run, with its point resolved once it is known.
  const std::optional<VehicleCommand>& active() const { return active_; }
  std::optional<double> desired_heading_deg() const { return desired_heading_deg_; }
  std::optional<double> desired_speed_mps() const { return desired_speed_mps_; }
  std::optional<double> distance_m() const {
    return keeper_ ? keeper_->distance_m() : std::nullopt;
  }
  // True once per arrival: the vehicle reached its point and now holds (for an event).
  bool take_arrival();

 private:
  void start_keeping(kinematics::Point p);

  vehicle::Vehicle& vehicle_;
  std::optional<VehicleCommand> active_;
  std::optional<StationKeeping> keeper_;
  std::optional<kinematics::Point> return_point_;
  std::optional<double> desired_heading_deg_;
  std::optional<double> desired_speed_mps_;
  bool stopped_ = false;  // all stop sent for the current behaviour or link loss
  bool arrival_reported_ = false;
};

}  // namespace avk::mission
