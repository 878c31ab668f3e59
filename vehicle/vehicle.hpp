#pragma once
// What a backseat sees of a vehicle, nothing more: navigation in, desired heading and speed out.
// The mission depends on this interface only; simulators and the M200 driver implement it.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avk::vehicle {

// A vehicle id names the vehicle in every list, stream topic and file name the station makes.
inline constexpr std::size_t kMaxVehicleIdBytes = 64;
// What is wrong with a vehicle id from outside (a config, an option, an imported file): empty,
// longer than kMaxVehicleIdBytes, or holding a control character (it goes into headers, CSV and
// log lines). A phrase to follow the id's name ("must not be empty"); none when it will do.
std::optional<std::string> vehicle_id_problem(std::string_view id);

// One navigation report (MOOS NAV_*). Local grid: x east, y north, metres; heading degrees
// clockwise from north in [0, 360); speed over ground m/s.
struct NavSample {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;
  std::optional<double> yaw_rate_dps;
};

// The guidance input (MOOS DESIRED_HEADING / DESIRED_SPEED), stamped with when it was set.
struct DesiredCommand {
  double t_s = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
};

// Actuator commands below the backseat controller (MOOS DESIRED_RUDDER / DESIRED_THRUST, and
// left/right thrust for differential-drive vehicles). Percent of full scale.
struct ActuatorCommand {
  double rudder_pct = 0.0;  // + turns to starboard
  double thrust_pct = 0.0;
  std::optional<double> left_pct;
  std::optional<double> right_pct;
};

enum class LinkState {
  live,          // navigation arriving
  stale,         // connected, but no navigation for longer than the stale limit
  disconnected,  // no link, or never any navigation
};
const char* to_string(LinkState s);
std::optional<LinkState> link_state_from_string(std::string_view s);
// Every state, in declaration order.
const std::vector<LinkState>& all_link_states();

struct VehicleInfo {
  std::string id;
  std::string kind;  // "usim", "catamaran:m200", "m200", ...
  double max_speed_mps = 0.0;
  std::optional<double> length_m;
};

class Vehicle {
 public:
  virtual ~Vehicle() = default;

  virtual const VehicleInfo& info() const = 0;

  // Navigation samples that arrived since the last call, oldest first (like MOOS mail): the
  // mission records every one of them.
  virtual std::vector<NavSample> take_nav() = 0;
  virtual std::optional<NavSample> last_nav() const = 0;

  // Stale navigation (older than stale_limit_s, default 2 s) is a fault the mission sees.
  virtual LinkState link_state(double now_s) const = 0;

  virtual void command(const DesiredCommand& desired) = 0;
  // Zero thrust now, whatever was desired; the next command() lifts it.
  virtual void all_stop(double now_s) = 0;

  virtual std::optional<DesiredCommand> last_command() const = 0;
  virtual std::optional<ActuatorCommand> last_actuators() const = 0;
};

// The command rule shared by every implementation: the heading wrapped to [0, 360). Throws
// std::invalid_argument for a time, heading or speed that is not finite, or a negative speed.
DesiredCommand checked_command(const DesiredCommand& desired);

// The link-state rule shared by every implementation.
LinkState link_state_from(const std::optional<NavSample>& last, bool connected, double now_s,
                          double stale_limit_s);

}  // namespace avk::vehicle
