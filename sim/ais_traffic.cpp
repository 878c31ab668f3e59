#include "sim/ais_traffic.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "kinematics/json_parse.hpp"
#include "mission/document_reader.hpp"
#include "sim/aivdm_encoder.hpp"

namespace avk::sim {

using nlohmann::json;

namespace {

constexpr double kMaxDistance_m = 100000.0;
constexpr double kMaxSpeed_mps = 50.0;
constexpr double kMaxAngle_deg = 3600.0;
constexpr std::size_t kMaxNameBytes = 20;  // what a type 5 message carries
constexpr std::size_t kMaxContacts = 1000;

std::string describe(const std::vector<mission::FieldError>& errors) {
  std::string s = "traffic scenario:";
  for (const auto& e : errors)
    s += " " + e.field + ": " + e.message + ";";
  s.pop_back();
  return s;
}

double wrap_deg(double deg) {
  const double w = std::fmod(deg, 360.0);
  return w < 0.0 ? w + 360.0 : w;
}

double bearing_deg(const kinematics::Point& from, const kinematics::Point& to) {
  return wrap_deg(std::atan2(to.x_m - from.x_m, to.y_m - from.y_m) * 180.0 / std::numbers::pi);
}

TrafficContact read_contact(const json& v, const std::string& path,
                            std::vector<mission::FieldError>& errors) {
  TrafficContact c;
  mission::DocumentReader r(v, path, errors);
  int mmsi = 0;
  if (r.get("mmsi", true)) r.integer("mmsi", mmsi, 1, 999999999);
  c.vessel.mmsi = static_cast<std::uint32_t>(mmsi);
  r.text("name", c.vessel.name, false, kMaxNameBytes);
  std::string ais_class = "A";
  r.text("class", ais_class, false, 1);
  if (ais_class == "B") {
    c.vessel.ais_class = AisClass::b;
  } else if (ais_class != "A") {
    r.error(r.at("class"), "expected \"A\" or \"B\"");
  }
  r.integer("ship_type", c.vessel.ship_type, 0, 99);
  r.number("speed_mps", c.speed_mps, 0.0, kMaxSpeed_mps, true);
  const json* start = r.get("start", false);
  const json* waypoints = r.get("waypoints", false);
  if (start && waypoints) {
    r.error(r.at("waypoints"), "give either start and course_deg, or waypoints");
  } else if (waypoints) {
    if (!waypoints->is_array() || waypoints->size() < 2) {
      r.error(r.at("waypoints"), "expected an array of at least 2 [x_m, y_m] points");
    } else {
      for (std::size_t k = 0; k < waypoints->size(); ++k) {
        if (const auto p = r.point((*waypoints)[k], r.at("waypoints") + "/" + std::to_string(k)))
          c.waypoints.push_back(*p);
      }
    }
  } else if (start) {
    if (const auto p = r.point(*start, r.at("start"))) c.start = *p;
    r.number("course_deg", c.course_deg, -kMaxAngle_deg, kMaxAngle_deg, true);
  } else if (r.ok()) {
    r.error(r.at("start"), "missing: give start and course_deg, or waypoints");
  }
  if (!start && r.get("course_deg", false))
    r.error(r.at("course_deg"), "a waypoint circuit takes its courses from its legs");
  r.finish();
  return c;
}

}  // namespace

TrafficScenarioError::TrafficScenarioError(std::vector<mission::FieldError> errors)
    : std::runtime_error(describe(errors)), errors_(std::move(errors)) {}

AisTraffic AisTraffic::parse(std::string_view json_text) {
  json doc;
  try {
    doc = kinematics::parse_json_bounded(json_text);
  } catch (const kinematics::JsonSyntaxError& e) {
    throw TrafficScenarioError(
        {{e.number_out_of_range() ? e.pointer() : std::string("json"), e.reason()}});
  }
  std::vector<mission::FieldError> errors;
  mission::DocumentReader root(doc, "", errors);
  vehicle::LatLon datum;
  if (const json* d = root.get("datum", true)) {
    mission::DocumentReader r(*d, root.at("datum"), errors);
    r.number("lat_deg", datum.lat_deg, -89.0, 89.0, true);
    r.number("lon_deg", datum.lon_deg, -180.0, 180.0, true);
    r.finish();
  }
  std::vector<TrafficContact> contacts;
  if (const json* list = root.get("contacts", true)) {
    if (!list->is_array() || list->empty() || list->size() > kMaxContacts) {
      root.error(root.at("contacts"),
                 "expected an array of 1 to " + std::to_string(kMaxContacts) + " contacts");
    } else {
      for (std::size_t k = 0; k < list->size(); ++k)
        contacts.push_back(
            read_contact((*list)[k], root.at("contacts") + "/" + std::to_string(k), errors));
    }
  }
  root.finish();
  if (!errors.empty()) throw TrafficScenarioError(std::move(errors));
  return AisTraffic(datum, std::move(contacts));
}

AisTraffic::AisTraffic(vehicle::LatLon datum, std::vector<TrafficContact> contacts)
    : grid_(datum.lat_deg, datum.lon_deg), contacts_(std::move(contacts)) {}

std::vector<TrafficState> AisTraffic::at(double t_s) const {
  std::vector<TrafficState> out;
  for (const auto& c : contacts_) {
    TrafficState s;
    s.vessel = c.vessel;
    s.speed_mps = c.speed_mps;
    const double run_m = c.speed_mps * t_s;
    if (c.waypoints.empty()) {
      const double rad = c.course_deg * std::numbers::pi / 180.0;
      s.x_m = c.start.x_m + run_m * std::sin(rad);
      s.y_m = c.start.y_m + run_m * std::cos(rad);
      s.course_deg = wrap_deg(c.course_deg);
    } else {
      // Around the closed circuit: the distance run, modulo its length, placed on its legs.
      const std::size_t n = c.waypoints.size();
      double circuit_m = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const auto& a = c.waypoints[i];
        const auto& b = c.waypoints[(i + 1) % n];
        circuit_m += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
      }
      double along_m = circuit_m > 0.0 ? std::fmod(run_m, circuit_m) : 0.0;
      if (along_m < 0.0) along_m += circuit_m;
      s.x_m = c.waypoints[0].x_m;
      s.y_m = c.waypoints[0].y_m;
      s.course_deg = bearing_deg(c.waypoints[0], c.waypoints[1 % n]);
      for (std::size_t i = 0; i < n; ++i) {
        const auto& a = c.waypoints[i];
        const auto& b = c.waypoints[(i + 1) % n];
        const double leg_m = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
        if (leg_m <= 0.0) continue;
        if (along_m <= leg_m || i + 1 == n) {
          const double f = std::min(along_m / leg_m, 1.0);
          s.x_m = a.x_m + f * (b.x_m - a.x_m);
          s.y_m = a.y_m + f * (b.y_m - a.y_m);
          s.course_deg = bearing_deg(a, b);
          break;
        }
        along_m -= leg_m;
      }
    }
    s.position = grid_.to_geodetic(s.x_m, s.y_m);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<std::string> AisTraffic::position_sentences(double t_s) const {
  std::vector<std::string> out;
  const int second = static_cast<int>(std::fmod(std::max(t_s, 0.0), 60.0));
  for (const auto& s : at(t_s)) {
    AisPositionMessage m;
    m.mmsi = s.vessel.mmsi;
    m.lat_deg = s.position.lat_deg;
    m.lon_deg = s.position.lon_deg;
    m.speed_mps = s.speed_mps;
    m.course_deg = s.course_deg;
    m.heading_deg = s.course_deg;
    m.utc_second = second;
    const bool class_a = s.vessel.ais_class == AisClass::a;
    if (class_a) m.nav_status = 0;  // under way using engine
    const auto lines = class_a ? encode_class_a_position(m) : encode_class_b_position(m);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  return out;
}

std::vector<std::string> AisTraffic::static_sentences() const {
  std::vector<std::string> out;
  int sequence = 0;
  for (const auto& c : contacts_) {
    if (c.vessel.name.empty()) continue;
    AisStaticMessage m;
    m.mmsi = c.vessel.mmsi;
    m.name = c.vessel.name;
    m.ship_type = c.vessel.ship_type;
    const auto lines = encode_static_voyage(m, sequence++ % 10);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  return out;
}

}  // namespace avk::sim
