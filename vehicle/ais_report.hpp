#pragma once
// What one AIS message says about a vessel, in the project's units: the fields of position
// reports (types 1, 2, 3: Class A; 18, 19: Class B) and static data (5: Class A; 24: Class B; 19
// carries both). Whatever the message leaves out, or marks "not available", is nullopt, so a
// consumer never mistakes AIS's sentinel values (lat 91, speed 102.3 kn, heading 511) for data.

#include <cstdint>
#include <optional>
#include <string>

namespace avk::vehicle {

struct AisReport {
  std::uint32_t mmsi = 0;
  int message_type = 0;  // 1 to 27 (ITU-R M.1371)
  // Position reports.
  std::optional<double> lat_deg;  // + north
  std::optional<double> lon_deg;  // + east
  // true: the position is better than 10 m (DGNSS); false: worse, or not known (plain GNSS).
  std::optional<bool> position_accuracy_high;
  std::optional<double> speed_mps;    // over ground
  std::optional<double> course_deg;   // over ground, clockwise from true north, [0, 360)
  std::optional<double> heading_deg;  // true heading, [0, 360)
  std::optional<int> nav_status;      // 0 under way using engine ... 14; 15 (undefined) is nullopt
  // Static data.
  std::optional<std::string> name;      // trailing spaces and '@' padding removed
  std::optional<std::string> callsign;  // the same
  std::optional<int> ship_type;         // 1 to 99; 0 (not available) is nullopt
  // When the station received it, on the clock of whoever made the report.
  double received_s = 0.0;
};

}  // namespace avk::vehicle
