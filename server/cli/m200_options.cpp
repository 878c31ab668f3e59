#include "server/cli/m200_options.hpp"

#include <cmath>

#include "server/cli/db_selection.hpp"

namespace avk::server {

std::optional<vehicle::LatLon> datum_from(const Args& a) {
  const auto d = a.number_list("datum", 2, "LAT,LON in decimal degrees");
  if (!d) return std::nullopt;
  if (std::abs((*d)[0]) > 90.0 || std::abs((*d)[1]) > 180.0)
    throw UsageError("--datum " + *a.get("datum") +
                     ": latitude must be within ±90, longitude ±180");
  return vehicle::LatLon{(*d)[0], (*d)[1]};
}

std::optional<vehicle::MarinePidConfig> pid_preset(const std::string& name) {
  if (name == "thesis_sim") return vehicle::MarinePidConfig::thesis_sim();
  if (name == "m200_in_water") return vehicle::MarinePidConfig::m200_in_water();
  return std::nullopt;
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
  if (const auto d = datum_from(a)) o.config.datum = *d;
  if (const auto pid = a.get("pid")) {
    const auto preset = pid_preset(*pid);
    if (!preset) throw UsageError("--pid must be thesis_sim or m200_in_water, got '" + *pid + "'");
    o.config.pid = *preset;
  }
  if (const auto hz = a.number("controller-hz")) {
    if (!(*hz >= 1.0 && *hz <= 100.0)) throw UsageError("--controller-hz must be in [1, 100]");
    o.config.controller_hz = *hz;
  }
  o.config.id = vehicle_id_option(a, "m200");
  return o;
}

}  // namespace avk::server
