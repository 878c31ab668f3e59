#include "server/cli/m200_options.hpp"

#include <charconv>
#include <cmath>

namespace avk::server {

namespace {

std::optional<double> to_number(const std::string& s) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

vehicle::LatLon parse_datum(const std::string& text, const std::string& option) {
  const auto comma = text.find(',');
  const auto lat = comma == std::string::npos ? std::nullopt : to_number(text.substr(0, comma));
  const auto lon = comma == std::string::npos ? std::nullopt : to_number(text.substr(comma + 1));
  if (!lat || !lon)
    throw UsageError(option + " expects LAT,LON in decimal degrees, got '" + text + "'");
  if (std::abs(*lat) > 90.0 || std::abs(*lon) > 180.0)
    throw UsageError(option + " " + text + ": latitude must be within ±90, longitude ±180");
  return {*lat, *lon};
}

std::optional<vehicle::M200Options> m200_options_from(const Args& a) {
  const auto where = a.get("m200");
  if (!where) return std::nullopt;
  vehicle::M200Options o;
  try {
    o.endpoint = vehicle::parse_m200_endpoint(*where);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--m200 ") + e.what());
  }
  if (const auto d = a.get("datum")) o.config.datum = parse_datum(*d);
  if (const auto pid = a.get("pid")) {
    if (*pid == "thesis_sim") {
      o.config.pid = vehicle::MarinePidConfig::thesis_sim();
    } else if (*pid == "m200_in_water") {
      o.config.pid = vehicle::MarinePidConfig::m200_in_water();
    } else {
      throw UsageError("--pid must be thesis_sim or m200_in_water, got '" + *pid + "'");
    }
  }
  if (const auto hz = a.number("controller-hz")) {
    if (!(*hz >= 1.0 && *hz <= 100.0)) throw UsageError("--controller-hz must be in [1, 100]");
    o.config.controller_hz = *hz;
  }
  o.config.id = a.get("vehicle-id").value_or("m200");
  return o;
}

}  // namespace avk::server
