#pragma once
// The messages of the station's Foxglove channels (app/foxglove/channels.hpp), built from domain
// values as JSON text: the same builders serve the live connection and a mission's MCAP file, so
// what a viewer shows live and on replay is the same data.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/corridor.hpp"
#include "kinematics/geometry.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::app::foxglove {

// Station clock seconds as the nanoseconds of a message's timestamp (negative times clamp to 0:
// the protocol's timestamps are unsigned).
std::uint64_t to_ns(double t_s);
double to_s(std::uint64_t t_ns);

// Foxglove's yaw (counter-clockwise from +x = east) of a heading (clockwise from north), as the
// quaternion of a rotation about z.
struct Quaternion {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};
Quaternion heading_quaternion(double heading_deg);

// One navigation report with the helm's command in force.
struct NavigationState {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  std::optional<double> yaw_rate_dps;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  std::optional<std::string> helm_mode;
  std::optional<std::int64_t> mission_id;
  std::optional<vehicle::LatLon> position;  // when the navigation (or a datum) gives it
};

std::string pose_message(const NavigationState& s);
std::string transform_message(const NavigationState& s, const std::string& vehicle_id);
// Needs s.position.
std::string location_message(const NavigationState& s, const std::string& vehicle_id);
std::string navigation_message(const NavigationState& s);

// foxglove.Log levels.
enum class LogLevel { info = 2, warning = 3, error = 4 };
// name: where it comes from ("<vehicle>/<event kind>"), so the Log panel can filter by it.
std::string log_message(double t_s, LogLevel level, const std::string& name,
                        const std::string& message);
// A stored mission event as a foxglove.Log that also carries the event's exact time ("t_s", the
// Log's timestamp is rounded to nanoseconds) and kind ("kind"), members the schema allows: what
// an MCAP import reads the event back from. name: "<vehicle>/<kind>".
std::string event_log_message(double t_s, LogLevel level, const std::string& vehicle_id,
                              const std::string& kind, const std::string& message);

// A predicted turn as drawn: the method's trajectory in the grid and, for the table, the band of
// its corridor.
struct ScenePrediction {
  std::string method;  // "avk", "model", "instantaneous"
  kinematics::Polyline trajectory;
  std::optional<kinematics::CorridorBand> corridor;
  // What the trajectory moves against, "ground" or "water" (GET /predict's relative_to), and the
  // current it was carried by, as read ("0.20 m/s toward 180 deg (live)"), else why none was.
  std::string frame;
  std::string current;
};

// The turn being flown (or the last one): where it started, what it was asked, what each
// method predicted, the CKT cell that answered and the track measured so far.
struct TurnScene {
  double t_s = 0.0;
  kinematics::Pose start;
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // signed: + right
  double goal_heading_deg = 0.0;
  std::string state;  // "running", "finished", "aborted", "rejected"
  std::vector<ScenePrediction> predictions;
  std::optional<std::string> cell_label;  // the CKT cell: speed, heading change, turns, advance
  kinematics::Polyline measured;
};

// SceneUpdate entities replace the previous message's entities of the same id, so a viewer holds
// one picture of the turn; the entity ids are "turn/<part>".
std::string turn_scene_message(const TurnScene& scene);
// The region's boundary and its buffer line (kinematics/polygon_inset.hpp), and the return point.
std::string region_scene_message(double t_s, const mission::OperatingRegion& region);

}  // namespace avk::app::foxglove
