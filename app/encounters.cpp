#include "app/encounters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "app/context.hpp"
#include "app/current.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/json_parse.hpp"
#include "mission/document_reader.hpp"
#include "sim/scheduler.hpp"
#include "sim/settle_leg.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::app {

namespace kin = avk::kinematics;
using nlohmann::json;

namespace {

constexpr double kMaxHorizonS = 600.0;
constexpr double kMaxSpeedMps = 50.0;
constexpr double kMaxAngleDeg = 3600.0;
constexpr double kMaxDistanceM = 100000.0;

// ---- the scenario file ----------------------------------------------------------------------

kin::Contact read_contact(const json& v, const std::string& path,
                          std::vector<mission::FieldError>& errors) {
  kin::Contact c;
  mission::DocumentReader r(v, path, errors);
  r.number("x_m", c.x_m, -kMaxDistanceM, kMaxDistanceM, true);
  r.number("y_m", c.y_m, -kMaxDistanceM, kMaxDistanceM, true);
  r.number("course_deg", c.course_deg, -kMaxAngleDeg, kMaxAngleDeg, true);
  r.number("speed_mps", c.speed_mps, 0.0, kMaxSpeedMps, true);
  r.finish();
  return c;
}

EncounterScenario read_scenario(const json& v, const std::string& path, double file_standoff_m,
                                std::vector<mission::FieldError>& errors) {
  EncounterScenario s;
  s.standoff_m = file_standoff_m;
  mission::DocumentReader r(v, path, errors);
  r.text("name", s.name, true, kMaxScenarioNameBytes);
  if (const json* own = r.get("own", true)) {
    mission::DocumentReader o(*own, r.at("own"), errors);
    o.number("heading_deg", s.own_heading_deg, -kMaxAngleDeg, kMaxAngleDeg, true);
    o.number("speed_mps", s.own_speed_mps, 0.0, kMaxSpeedMps, true, true);
    o.finish();
  }
  if (const json* contacts = r.get("contacts", true)) {
    if (!contacts->is_array() || contacts->empty()) {
      r.error(r.at("contacts"), "expected a non-empty array of contacts");
    } else {
      for (std::size_t k = 0; k < contacts->size(); ++k)
        s.contacts.push_back(
            read_contact((*contacts)[k], r.at("contacts") + "/" + std::to_string(k), errors));
    }
  }
  r.number("standoff_m", s.standoff_m, 0.0, kMaxDistanceM, false, true);
  r.finish();
  return s;
}

// ---- one maneuver flown ---------------------------------------------------------------------

std::optional<Error> check_contacts(const std::vector<kin::Contact>& contacts) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const auto& c = contacts[k];
    const std::string at = "contacts/" + std::to_string(k) + "/";
    if (!std::isfinite(c.x_m) || !std::isfinite(c.y_m))
      return invalid_argument(at + "position", "must be finite");
    if (!std::isfinite(c.course_deg)) return invalid_argument(at + "course_deg", "must be finite");
    if (!(c.speed_mps >= 0.0 && std::isfinite(c.speed_mps)))
      return invalid_argument(at + "speed_mps", "must be >= 0 and finite");
  }
  return std::nullopt;
}

std::optional<Error> check_maneuver(const SimulatedManeuverQuery& q) {
  if (!(q.own_speed_mps > 0.0 && std::isfinite(q.own_speed_mps)))
    return invalid_argument("own_speed", "must be > 0 and finite (m/s)");
  if (!std::isfinite(q.own_heading_deg)) return invalid_argument("own_heading", "must be finite");
  if (!(std::abs(q.dheading_deg) <= 180.0))
    return invalid_argument("dheading", "must be in [-180, 180]");
  if (q.speed_mps && !(*q.speed_mps > 0.0 && std::isfinite(*q.speed_mps)))
    return invalid_argument("speed", "must be > 0 and finite (m/s)");
  if (!(q.horizon_s > 0.0 && q.horizon_s <= kMaxHorizonS))
    return invalid_argument("horizon", "must be > 0 and <= 600 s");
  return check_contacts(q.contacts);
}

// A turn of about 180 deg would go whichever way the heading noise points the controller's
// error; the helm leads such a turn by commanding 90 deg to the chosen side until the vehicle has
// turned 45 deg, then the goal.
constexpr double kLeadAboveDeg = 170.0;
constexpr double kLeadDeg = 90.0;
constexpr double kLeadUntilDeg = 45.0;

}  // namespace

Result<EncounterFile> parse_encounter_file(std::string_view json_text) {
  json doc;
  try {
    doc = kin::parse_json_bounded(json_text);
  } catch (const kin::JsonSyntaxError& e) {
    return invalid_argument(e.pointer(), "the encounter file is not JSON: " + e.reason());
  } catch (const kin::ParseError& e) {
    return invalid_argument(e.field(), "the encounter file is not valid: " + e.message());
  }
  std::vector<mission::FieldError> errors;
  EncounterFile f;
  mission::DocumentReader root(doc, "", errors);
  int version = 0;
  if (root.get("schema_version", true)) {
    root.integer("schema_version", version, 1, 1);
  }
  root.number("standoff_m", f.standoff_m, 0.0, kMaxDistanceM, false, true);
  root.number("horizon_s", f.horizon_s, 0.0, kMaxHorizonS, false, true);
  if (const json* scenarios = root.get("scenarios", true)) {
    if (!scenarios->is_array() || scenarios->empty()) {
      root.error("/scenarios", "expected a non-empty array of scenarios");
    } else {
      std::set<std::string> names;
      for (std::size_t i = 0; i < scenarios->size(); ++i) {
        const std::string path = "/scenarios/" + std::to_string(i);
        f.scenarios.push_back(read_scenario((*scenarios)[i], path, f.standoff_m, errors));
        const std::string& name = f.scenarios.back().name;
        if (!name.empty() && !names.insert(name).second)
          errors.push_back({path + "/name", "duplicate scenario name '" + name + "'"});
      }
    }
  }
  root.finish();
  if (!errors.empty()) {
    Error e = invalid_argument(errors.front().field, "the encounter file is not valid");
    for (const auto& fe : errors)
      e.fields.push_back({fe.field, fe.message});
    return e;
  }
  f.schema_version = version;
  return f;
}

Result<SimulatedManeuver> simulate_maneuver(const SimulatedManeuverQuery& q) {
  if (auto e = check_maneuver(q)) return *e;
  sim::SchedulerOptions so = q.setup.scheduler;
  so.seed = q.seed;
  so.start_time_s = 0.0;
  sim::Scheduler scheduler(so);
  sim::SimVehicleConfig vc = q.setup.vehicle;
  vc.seed = q.seed;
  vc.start_x_m = 0.0;
  vc.start_y_m = 0.0;
  vc.start_heading_deg = q.own_heading_deg;
  vc.start_speed_mps = q.own_speed_mps;
  sim::SimVehicle vehicle(vc, scheduler);

  const sim::SettleRule rule{};
  sim::SettleLeg settle(rule, q.own_speed_mps, q.own_heading_deg);
  const double course = q.own_heading_deg;
  const double speed_after = q.speed_mps.value_or(q.own_speed_mps);
  const double side = q.dheading_deg < 0.0 ? -1.0 : 1.0;
  bool leading = std::abs(q.dheading_deg) > kLeadAboveDeg;
  double turned_deg = 0.0;
  std::optional<double> last_heading;
  std::optional<double> command_s;
  sim::TruthSample at_command{};
  std::vector<sim::TruthSample> truth;

  scheduler.add("helm", q.setup.helm_hz, [&](double now) {
    for (const auto& s : vehicle.take_nav()) {
      if (!command_s) {
        settle.update(s);
      } else if (leading) {
        if (last_heading) turned_deg += kin::angle180_deg(s.heading_deg - *last_heading);
        last_heading = s.heading_deg;
        if (side * turned_deg >= kLeadUntilDeg) leading = false;
      }
    }
    double desired = course;
    double desired_speed = q.own_speed_mps;
    if (!command_s && settle.done(now)) {
      command_s = now;
      at_command = vehicle.truth();
      at_command.t_s = now;
      last_heading = settle.newest()->heading_deg;
    }
    if (command_s) {
      desired = course + (leading ? side * kLeadDeg : q.dheading_deg);
      desired_speed = speed_after;
    }
    vehicle.command({now, kin::wrap360_deg(desired), desired_speed});
  });
  // Ground truth at the navigation rate (the plant's publication rate) after the command.
  scheduler.add("truth", vc.plant_hz, [&](double now) {
    if (!command_s || now <= *command_s) return;
    const sim::TruthSample t = vehicle.truth();
    if (t.t_s > (truth.empty() ? *command_s : truth.back().t_s)) truth.push_back(t);
    if (now >= *command_s + q.horizon_s) scheduler.request_stop();
  });
  scheduler.run_until(rule.max_settle_s + q.horizon_s + 10.0);
  if (!command_s) return internal_error("the simulated vehicle never delivered navigation");

  SimulatedManeuver out;
  out.settle_s = *command_s;
  out.heading_at_command_deg = at_command.heading_deg;
  out.speed_at_command_mps = at_command.speed_over_ground_mps;
  out.track.push_back({0.0, 0.0, 0.0});
  for (const auto& t : truth) {
    out.track.push_back({t.t_s - *command_s, t.x_m - at_command.x_m, t.y_m - at_command.y_m});
  }
  out.min_cpa_m = std::numeric_limits<double>::infinity();
  for (const auto& c : q.contacts) {
    out.cpa.push_back(kin::closest_approach(out.track, c));
    out.min_cpa_m = std::min(out.min_cpa_m, out.cpa.back().distance_m);
  }
  if (q.contacts.empty()) out.min_cpa_m = 0.0;
  return out;
}

std::string encounter_file_json(const EncounterFile& file) {
  std::string out = "{\"schema_version\": " + std::to_string(file.schema_version) +
                    ", \"standoff_m\": " + json(file.standoff_m).dump() +
                    ", \"horizon_s\": " + json(file.horizon_s).dump() + ",\n \"scenarios\": [\n";
  for (std::size_t i = 0; i < file.scenarios.size(); ++i) {
    const EncounterScenario& s = file.scenarios[i];
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (const auto& c : s.contacts) {
      contacts.push_back({{"x_m", c.x_m},
                          {"y_m", c.y_m},
                          {"course_deg", c.course_deg},
                          {"speed_mps", c.speed_mps}});
    }
    nlohmann::ordered_json j = {
        {"name", s.name},
        {"own", {{"heading_deg", s.own_heading_deg}, {"speed_mps", s.own_speed_mps}}},
        {"contacts", contacts}};
    if (s.standoff_m != file.standoff_m) j["standoff_m"] = s.standoff_m;
    out += "  " + j.dump() + (i + 1 < file.scenarios.size() ? ",\n" : "\n");
  }
  return out + " ]}\n";
}

}  // namespace avk::app
