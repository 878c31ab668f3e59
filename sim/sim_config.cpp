#include "sim/sim_config.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "kinematics/json_parse.hpp"
#include "kinematics/parse_error.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::sim {

using kinematics::ParseError;
using nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw ParseError(path, 0, what);
}

// Walks one JSON object: every key must be handled by exactly one reader, so a typo is an error.
class ObjectReader {
 public:
  ObjectReader(const json& obj, std::string path) : obj_(obj), path_(std::move(path)) {
    if (!obj.is_object()) fail(path_.empty() ? "/" : path_, "expected an object");
  }

  void number(const char* key, double& target, double min, double max) {
    handled_.insert(key);
    const auto it = obj_.find(key);
    if (it == obj_.end()) return;
    const std::string p = path_ + "/" + key;
    if (!it->is_number()) fail(p, "expected a number");
    const double v = it->get<double>();
    if (!std::isfinite(v) || v < min || v > max) {
      fail(p, "must be between " + json(min).dump() + " and " + json(max).dump());
    }
    target = v;
  }

  void optional_number(const char* key, std::optional<double>& target, double min, double max) {
    double v = 0.0;
    const bool present = obj_.contains(key) && !obj_.at(key).is_null();
    if (present) {
      number(key, v, min, max);
      target = v;
    } else {
      handled_.insert(key);
    }
  }

  void boolean(const char* key, bool& target) {
    handled_.insert(key);
    const auto it = obj_.find(key);
    if (it == obj_.end()) return;
    if (!it->is_boolean()) fail(path_ + "/" + key, "expected true or false");
    target = it->get<bool>();
  }

  void object(const char* key, const std::function<void(ObjectReader&)>& read) {
    handled_.insert(key);
    const auto it = obj_.find(key);
    if (it == obj_.end()) return;
    ObjectReader sub(*it, path_ + "/" + key);
    read(sub);
    sub.finish();
  }

  std::optional<std::string> string(const char* key) {
    handled_.insert(key);
    const auto it = obj_.find(key);
    if (it == obj_.end()) return std::nullopt;
    if (!it->is_string()) fail(path_ + "/" + key, "expected a string");
    return it->get<std::string>();
  }

  void finish() const {
    for (const auto& [k, v] : obj_.items()) {
      if (!handled_.count(k)) fail(path_ + "/" + k, "unknown field '" + k + "'");
    }
  }

 private:
  const json& obj_;
  std::string path_;
  std::set<std::string> handled_;
};

void read_gains(ObjectReader& r, vehicle::PidGains& g) {
  r.number("kp", g.kp, 0.0, 1e3);
  r.number("kd", g.kd, 0.0, 1e3);
  r.number("ki", g.ki, 0.0, 1e3);
  r.number("integral_limit", g.integral_limit, 0.0, 100.0);
}

}  // namespace

double SimSetup::vehicle_max_speed_mps() const {
  return max_speed_mps(vehicle);
}

SimSetup default_sim_setup(vehicle::VehicleKind kind) {
  SimSetup s;
  s.vehicle = sim_vehicle_defaults(kind);
  // In the water the thesis ran pHelmIvP at 10 Hz (§3.4.2), having seen turns pass their goal
  // between helm ticks at 4 Hz (§4.5).
  if (kind == vehicle::VehicleKind::catamaran_m200) s.helm_hz = 10.0;
  return s;
}

SimSetup default_sim_setup(std::string_view kind) {
  return default_sim_setup(sim_vehicle_defaults(kind).kind);
}

SimSetup parse_sim_config(std::string_view json_text, const std::string& default_kind) {
  json doc;
  try {
    doc = kinematics::parse_json_bounded(json_text);
  } catch (const kinematics::JsonSyntaxError& e) {
    // A number too large for a double names its field; nlohmann's own exceptions never leave.
    if (e.number_out_of_range()) fail(e.pointer(), e.reason());
    throw ParseError("json", e.position(), "sim config is not valid JSON: " + e.reason());
  }
  ObjectReader root(doc, "");
  std::string kind = default_kind;
  if (const auto k = root.string("vehicle")) kind = *k;
  SimSetup s;
  try {
    s = default_sim_setup(kind);
  } catch (const std::invalid_argument& e) {
    fail("/vehicle", e.what());
  }
  SimVehicleConfig& v = s.vehicle;
  if (const auto id = root.string("vehicle_id")) {
    if (const auto why = vehicle::vehicle_id_problem(*id)) fail("/vehicle_id", *why);
    v.id = *id;
  }
  root.object("ticks_hz", [&](ObjectReader& r) {
    r.number("plant", v.plant_hz, 0.1, 1000.0);
    r.number("controller", v.controller_hz, 0.1, 1000.0);
    r.number("helm", s.helm_hz, 0.1, 1000.0);
  });
  root.object("pid", [&](ObjectReader& r) {
    if (const auto preset = r.string("preset")) {
      if (*preset == "thesis_sim") {
        v.pid = vehicle::MarinePidConfig::thesis_sim();
      } else if (*preset == "m200_in_water") {
        v.pid = vehicle::MarinePidConfig::m200_in_water();
      } else {
        fail("/pid/preset", "unknown preset '" + *preset + "' (thesis_sim, m200_in_water)");
      }
    }
    r.object("yaw", [&](ObjectReader& g) { read_gains(g, v.pid.yaw); });
    r.object("speed", [&](ObjectReader& g) { read_gains(g, v.pid.speed); });
    r.number("max_rudder_pct", v.pid.max_rudder_pct, 0.0, 100.0);
    r.number("max_thrust_pct", v.pid.max_thrust_pct, 0.0, 100.0);
    r.number("speed_factor", v.pid.speed_factor, 0.0, 1000.0);
  });
  root.object("usim", [&](ObjectReader& r) {
    r.number("turn_rate", v.usim.turn_rate, 0.0, 100.0);
    r.number("thrust_factor", v.usim.thrust_factor, 0.01, 1000.0);
    r.number("max_acceleration_mps2", v.usim.max_acceleration_mps2, 0.0, 100.0);
    r.number("max_deceleration_mps2", v.usim.max_deceleration_mps2, 0.0, 100.0);
    r.number("rotate_speed_dps", v.usim.rotate_speed_dps, -360.0, 360.0);
    r.number("drift_x_mps", v.usim.drift_x_mps, -10.0, 10.0);
    r.number("drift_y_mps", v.usim.drift_y_mps, -10.0, 10.0);
  });
  root.object("current", [&](ObjectReader& r) {
    r.number("speed_mps", v.environment.current.speed_mps, 0.0, 5.0);
    r.number("toward_deg", v.environment.current.toward_deg, 0.0, 360.0);
  });
  root.object("wind", [&](ObjectReader& r) {
    r.number("mean_speed_mps", v.environment.wind.mean_speed_mps, 0.0, 40.0);
    r.number("from_deg", v.environment.wind.from_deg, 0.0, 360.0);
    r.number("gust_sigma_mps", v.environment.wind.gust_sigma_mps, 0.0, 20.0);
    r.number("gust_time_constant_s", v.environment.wind.gust_time_constant_s, 0.1, 3600.0);
  });
  root.object("sensors", [&](ObjectReader& r) {
    r.number("gnss_sigma_m", v.sensors.gnss_sigma_m, 0.0, 100.0);
    r.number("compass_sigma_deg", v.sensors.compass_sigma_deg, 0.0, 90.0);
    r.number("speed_sigma_mps", v.sensors.speed_sigma_mps, 0.0, 10.0);
    r.optional_number("heading_from_course_above_mps", v.sensors.heading_from_course_above_mps, 0.0,
                      100.0);
    r.number("latency_s", v.sensors.latency_s, 0.0, 10.0);
  });
  double seed = static_cast<double>(s.scheduler.seed);
  root.number("seed", seed, 0.0, 9007199254740992.0);
  if (std::floor(seed) != seed) fail("/seed", "must be a whole number");
  s.scheduler.seed = static_cast<std::uint64_t>(seed);
  root.number("jitter_fraction", s.scheduler.jitter_fraction, 0.0, 0.99);
  root.boolean("random_phases", s.scheduler.random_phases);
  root.finish();
  return s;
}

}  // namespace avk::sim
