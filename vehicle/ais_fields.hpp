#pragma once
// The scaled integers of AIS position and static fields (ITU-R M.1371, as gpsd's libgps hands them
// over unscaled) and their conversions to the project's units. Each "not available" value, and
// every value outside the field's range, converts to nullopt. The encoder of the simulated
// traffic (sim/aivdm_encoder.hpp) writes the same integers back.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace avk::vehicle {

// Latitude and longitude of position reports: 1/10000 minute, that is 1/600000 degree.
inline constexpr double kAisLatLonPerDeg = 600000.0;
inline constexpr std::int32_t kAisLonNotAvailable = 181 * 600000;
inline constexpr std::int32_t kAisLatNotAvailable = 91 * 600000;
// Speed over ground: 0.1 knot; 1022 means 102.2 kn or faster.
inline constexpr unsigned kAisSpeedNotAvailable = 1023;
inline constexpr unsigned kAisSpeedMax = 1022;
// Course over ground: 0.1 degree.
inline constexpr unsigned kAisCourseNotAvailable = 3600;
// True heading: whole degrees.
inline constexpr unsigned kAisHeadingNotAvailable = 511;
inline constexpr unsigned kAisNavStatusNotDefined = 15;
inline constexpr unsigned kAisShipTypeNotAvailable = 0;

std::optional<double> ais_lat_deg(std::int32_t lat);
std::optional<double> ais_lon_deg(std::int32_t lon);
std::optional<double> ais_speed_mps(unsigned deciknots);
std::optional<double> ais_course_deg(unsigned decidegrees);
std::optional<double> ais_heading_deg(unsigned degrees);
std::optional<int> ais_nav_status(unsigned status);
std::optional<int> ais_ship_type(unsigned type);
// Six-bit text is padded with '@' (and often spaces) to its field's width: both are cut from the
// end; an empty result is nullopt.
std::optional<std::string> ais_text(std::string_view padded);

}  // namespace avk::vehicle
