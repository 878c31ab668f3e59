#pragma once
// Simulated AIS traffic for the simulator deployment (docs/ais.md): vessels on straight tracks or
// on closed waypoint circuits at constant speed, read from a scenario file, their state at any
// time t since the scenario's start, and the AIVDM sentences their transponders would send then.
//
// The scenario file (examples/traffic-*.json):
//   {"datum": {"lat_deg": ..., "lon_deg": ...},
//    "contacts": [{"mmsi": 366000001, "name": "...", "class": "A" or "B", "ship_type": 0-99,
//                  "speed_mps": ..., and either "start": [x_m, y_m], "course_deg": ...
//                  or "waypoints": [[x_m, y_m], ...] (at least 2; after the last, back to the
//                  first)}]}
// Positions are on the local grid about the datum (x east, y north, metres).

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/geometry.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::sim {

enum class AisClass { a, b };

// Who a contact is, as its static data says.
struct TrafficVessel {
  std::uint32_t mmsi = 0;
  std::string name;
  AisClass ais_class = AisClass::a;
  int ship_type = 0;
};

struct TrafficContact {
  TrafficVessel vessel;
  double speed_mps = 0.0;
  // A straight track from start, or a closed circuit of waypoints (when there are any).
  kinematics::Point start;
  double course_deg = 0.0;
  std::vector<kinematics::Point> waypoints;
};

struct TrafficState {
  TrafficVessel vessel;
  double x_m = 0.0;
  double y_m = 0.0;
  vehicle::LatLon position;
  double course_deg = 0.0;  // clockwise from north, [0, 360)
  double speed_mps = 0.0;
};

// A scenario file with bad fields: every one of them, each named by its JSON pointer.
class TrafficScenarioError : public std::runtime_error {
 public:
  explicit TrafficScenarioError(std::vector<mission::FieldError> errors);
  const std::vector<mission::FieldError>& errors() const { return errors_; }

 private:
  std::vector<mission::FieldError> errors_;
};

class AisTraffic {
 public:
  // Throws TrafficScenarioError.
  static AisTraffic parse(std::string_view json_text);
  AisTraffic(vehicle::LatLon datum, std::vector<TrafficContact> contacts);

  const vehicle::LatLon& datum() const { return grid_.datum(); }
  const std::vector<TrafficContact>& contacts() const { return contacts_; }

  std::vector<TrafficState> at(double t_s) const;
  // Every contact's position report at t (type 1 for Class A, 18 for Class B), with its UTC
  // second taken from t.
  std::vector<std::string> position_sentences(double t_s) const;
  // Every contact's static data (type 5) that has a name; Class B units send type 24, which the
  // encoder does not write, so their names go out as type 5 too.
  std::vector<std::string> static_sentences() const;

 private:
  vehicle::LocalGrid grid_;
  std::vector<TrafficContact> contacts_;
};

}  // namespace avk::sim
