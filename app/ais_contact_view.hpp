#pragma once
// A vessel of the AIS traffic table (app/ais_contacts.hpp) as the use cases answer it.

#include <cstdint>
#include <optional>
#include <string>

namespace avk::app {

// One vessel with a known position, as of the snapshot.
struct AisContactView {
  std::uint32_t mmsi = 0;
  std::string name;  // empty until static data arrives
  std::string callsign;
  std::optional<int> ship_type;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double x_m = 0.0;  // east of the datum
  double y_m = 0.0;  // north of the datum
  std::optional<double> course_deg;
  std::optional<double> speed_mps;
  std::optional<double> heading_deg;
  bool position_accuracy_high = false;
  double age_s = 0.0;  // since the last position report
};

}  // namespace avk::app
