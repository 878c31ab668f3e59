#include "vehicle/ais_fields.hpp"

#include "vehicle/nmea.hpp"

namespace avk::vehicle {

// 91 and 181 degrees are "not available"; anything past the poles or the antimeridian is junk.
std::optional<double> ais_lat_deg(std::int32_t lat) {
  if (lat > 90 * 600000 || lat < -90 * 600000) return std::nullopt;
  return lat / kAisLatLonPerDeg;
}

std::optional<double> ais_lon_deg(std::int32_t lon) {
  if (lon > 180 * 600000 || lon < -180 * 600000) return std::nullopt;
  return lon / kAisLatLonPerDeg;
}

std::optional<double> ais_speed_mps(unsigned deciknots) {
  if (deciknots >= kAisSpeedNotAvailable) return std::nullopt;
  return deciknots / 10.0 * kMetresPerSecondPerKnot;
}

std::optional<double> ais_course_deg(unsigned decidegrees) {
  if (decidegrees >= kAisCourseNotAvailable) return std::nullopt;
  return decidegrees / 10.0;
}

std::optional<double> ais_heading_deg(unsigned degrees) {
  if (degrees >= 360) return std::nullopt;  // 511 is "not available"; 360 to 510 are not used
  return static_cast<double>(degrees);
}

std::optional<int> ais_nav_status(unsigned status) {
  if (status >= kAisNavStatusNotDefined) return std::nullopt;
  return static_cast<int>(status);
}

std::optional<int> ais_ship_type(unsigned type) {
  if (type == kAisShipTypeNotAvailable || type > 99) return std::nullopt;
  return static_cast<int>(type);
}

std::optional<std::string> ais_text(std::string_view padded) {
  const std::size_t end = padded.find_last_not_of(" @");
  if (end == std::string_view::npos) return std::nullopt;
  return std::string(padded.substr(0, end + 1));
}

}  // namespace avk::vehicle
