#include "server/cli/fleet_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "server/cli/m200_options.hpp"
#include "sim/sim_config.hpp"
#include "vehicle/m200.hpp"

namespace avk::server {

namespace {

using nlohmann::json;

struct FleetError : std::runtime_error {
  FleetError(const std::string& pointer, const std::string& what)
      : std::runtime_error(pointer + ": " + what) {}
};

double number_at(const json& o, const std::string& key, const std::string& at, double fallback) {
  if (!o.contains(key)) return fallback;
  const json& v = o.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw FleetError(at + "/" + key, "must be a number");
  return v.get<double>();
}

std::string text_at(const json& o, const std::string& key, const std::string& at) {
  const json& v = o.at(key);
  if (!v.is_string() || v.get<std::string>().empty())
    throw FleetError(at + "/" + key, "must be a non-empty string");
  return v.get<std::string>();
}

std::string read_text(const std::filesystem::path& p, const std::string& at) {
  std::ifstream in(p);
  if (!in) throw FleetError(at, "cannot read " + p.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The ids a fleet vehicle may have: they are path segments of the API (/vehicles/{vid}).
void check_id(const std::string& id, const std::string& at) {
  for (const char c : id)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ||
          c == ':'))
      throw FleetError(at, "'" + id + "' may hold only letters, digits and - _ . :");
}

app::VehicleLoopOptions simulated(const json& v, const std::string& at,
                                  const std::filesystem::path& folder) {
  static const std::set<std::string> known = {"id", "vehicle", "sim_config", "seed", "start"};
  for (const auto& [key, _] : v.items())
    if (!known.contains(key))
      throw FleetError(at + "/" + key,
                       "unknown field (a simulated vehicle has id, vehicle, "
                       "sim_config, seed, start)");
  const std::string kind = v.contains("vehicle") ? text_at(v, "vehicle", at) : "catamaran:m200";
  app::VehicleLoopOptions o;
  try {
    if (v.contains("sim_config")) {
      const std::filesystem::path file = folder / text_at(v, "sim_config", at);
      o.setup = sim::parse_sim_config(read_text(file, at + "/sim_config"), kind);
    } else {
      o.setup = sim::default_sim_setup(kind);
    }
  } catch (const FleetError&) {
    throw;
  } catch (const std::exception& e) {
    throw FleetError(at + (v.contains("sim_config") ? "/sim_config" : "/vehicle"), e.what());
  }
  const double seed = number_at(v, "seed", at, static_cast<double>(o.setup.scheduler.seed));
  if (seed < 0 || std::floor(seed) != seed)
    throw FleetError(at + "/seed", "must be a whole number >= 0");
  o.setup.scheduler.seed = static_cast<std::uint64_t>(seed);
  o.setup.vehicle.id = text_at(v, "id", at);
  if (v.contains("start")) {
    const json& s = v.at("start");
    const std::string sat = at + "/start";
    if (!s.is_object()) throw FleetError(sat, "must be an object {x_m, y_m, heading_deg}");
    o.start.x_m = number_at(s, "x_m", sat, 0.0);
    o.start.y_m = number_at(s, "y_m", sat, 0.0);
    o.start.heading_deg = number_at(s, "heading_deg", sat, 0.0);
    if (o.start.heading_deg < 0.0 || o.start.heading_deg >= 360.0)
      throw FleetError(sat + "/heading_deg", "must be in [0, 360) degrees clockwise from north");
  }
  return o;
}

app::VehicleLoopOptions m200(const json& v, const std::string& at,
                             const std::optional<vehicle::LatLon>& datum) {
  static const std::set<std::string> known = {"id", "m200", "pid", "controller_hz"};
  for (const auto& [key, _] : v.items())
    if (!known.contains(key))
      throw FleetError(at + "/" + key, "unknown field (an M200 has id, m200, pid, controller_hz)");
  vehicle::M200Options m;
  try {
    m.endpoint = vehicle::parse_m200_endpoint(text_at(v, "m200", at));
  } catch (const std::invalid_argument& e) {
    throw FleetError(at + "/m200", e.what());
  }
  if (datum) m.config.datum = *datum;
  if (v.contains("pid")) {
    const std::string pid = text_at(v, "pid", at);
    const auto preset = pid_preset(pid);
    if (!preset)
      throw FleetError(at + "/pid", "must be thesis_sim or m200_in_water, got '" + pid + "'");
    m.config.pid = *preset;
  }
  const double hz = number_at(v, "controller_hz", at, m.config.controller_hz);
  if (!(hz >= 1.0 && hz <= 100.0)) throw FleetError(at + "/controller_hz", "must be in [1, 100]");
  m.config.controller_hz = hz;
  m.config.id = text_at(v, "id", at);
  app::VehicleLoopOptions o;
  o.kind = vehicle::VehicleKind::m200;
  o.m200 = std::move(m);
  return o;
}

}  // namespace

std::vector<app::VehicleLoopOptions> parse_fleet_file(const std::string& path,
                                                      const std::string& text,
                                                      double realtime_factor, double start_clock_s,
                                                      const std::optional<vehicle::LatLon>& datum) {
  try {
    const json doc = json::parse(text);
    if (!doc.is_object() || !doc.contains("vehicles") || !doc.at("vehicles").is_array() ||
        doc.at("vehicles").empty())
      throw FleetError("/vehicles", "must be a non-empty array of vehicles");
    for (const auto& [key, _] : doc.items())
      if (key != "vehicles") throw FleetError("/" + key, "unknown field (a fleet has vehicles)");
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    std::vector<app::VehicleLoopOptions> out;
    std::set<std::string> ids;
    for (std::size_t i = 0; i < doc.at("vehicles").size(); ++i) {
      const json& v = doc.at("vehicles")[i];
      const std::string at = "/vehicles/" + std::to_string(i);
      if (!v.is_object()) throw FleetError(at, "must be an object");
      if (!v.contains("id")) throw FleetError(at + "/id", "is missing: every vehicle needs an id");
      const std::string id = text_at(v, "id", at);
      check_id(id, at + "/id");
      if (!ids.insert(id).second)
        throw FleetError(at + "/id", "'" + id + "' names an earlier vehicle too");
      app::VehicleLoopOptions o =
          v.contains("m200") ? m200(v, at, datum) : simulated(v, at, folder);
      o.realtime_factor = realtime_factor;
      o.start_clock_s = start_clock_s;
      out.push_back(std::move(o));
    }
    return out;
  } catch (const json::parse_error& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  } catch (const FleetError& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace avk::server
