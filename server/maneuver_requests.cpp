#include "server/maneuver_requests.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "mission/document_reader.hpp"
#include "server/api_params.hpp"
#include "server/serialize.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

using Reader = mission::DocumentReader;
using Errors = std::vector<mission::FieldError>;

// What mission::DocumentReader does not read itself. A null member counts as absent.
const json* present(Reader& r, const char* key, bool required) {
  const json* v = r.get(key, required);
  if (v && v->is_null()) {
    if (required) r.error(r.at(key), "missing required field");
    return nullptr;
  }
  return v;
}

std::optional<double> number(Reader& r, const char* key, double min, double max, bool required,
                             bool min_exclusive = false) {
  if (!present(r, key, required)) return std::nullopt;
  // The reader sets the target only for a good value.
  double v = std::numeric_limits<double>::quiet_NaN();
  r.number(key, v, min, max, required, min_exclusive);
  return std::isnan(v) ? std::nullopt : std::optional<double>(v);
}

std::optional<bool> boolean(Reader& r, const char* key) {
  const json* v = present(r, key, false);
  if (!v) return std::nullopt;
  if (!v->is_boolean()) {
    r.error(r.at(key), "expected true or false");
    return std::nullopt;
  }
  return v->get<bool>();
}

// "over_ground" (true) or "through_water" (false).
std::optional<bool> speed_reference(Reader& r, const char* key) {
  const json* v = present(r, key, false);
  if (!v) return std::nullopt;
  if (v->is_string() && (*v == "over_ground" || *v == "through_water")) return *v == "over_ground";
  r.error(std::string("/") + key, R"(expected "over_ground" or "through_water")");
  return std::nullopt;
}

std::optional<app::PredictionMethod> method(Reader& r, const char* key) {
  const json* v = present(r, key, false);
  if (!v) return std::nullopt;
  const auto m =
      v->is_string() ? app::prediction_method_from_string(v->get<std::string>()) : std::nullopt;
  if (!m) r.error(r.at(key), "must be avk, model or instantaneous");
  return m;
}

std::optional<std::int64_t> id(Reader& r, const char* key) {
  const json* v = present(r, key, false);
  if (!v) return std::nullopt;
  if (!v->is_number_integer() || v->get<std::int64_t>() <= 0) {
    r.error(r.at(key), "expected a positive whole number, got " + describe_value(*v));
    return std::nullopt;
  }
  return v->get<std::int64_t>();
}

// A non-empty array of at most max_count elements.
const json* array(Reader& r, const char* key, bool required, std::size_t max_count) {
  const json* v = present(r, key, required);
  if (!v) return nullptr;
  if (!v->is_array() || v->empty()) {
    r.error(r.at(key), "expected a non-empty array");
    return nullptr;
  }
  if (v->size() > max_count) {
    r.error(r.at(key), "holds " + std::to_string(v->size()) + " elements, at most " +
                           std::to_string(max_count) + " are taken");
    return nullptr;
  }
  return v;
}

constexpr double kMaxCoordinateM = 1e6;
constexpr double kMaxSpeedMps = 20.0;  // own vehicle; the station's vehicles are small
constexpr double kMaxContactSpeedMps = 50.0;

struct Own {
  kinematics::Pose pose;
  double speed_mps = 1.0;
};

Own own_of(Reader& body, Errors& errors) {
  Own own;
  const json* v = present(body, "own", true);
  if (!v) return own;
  Reader r(*v, "/own", errors);
  r.number("x_m", own.pose.x_m, -kMaxCoordinateM, kMaxCoordinateM);
  r.number("y_m", own.pose.y_m, -kMaxCoordinateM, kMaxCoordinateM);
  r.number("heading_deg", own.pose.heading_deg, -360.0, 360.0, true);
  r.number("speed_mps", own.speed_mps, 0.0, kMaxSpeedMps, true, true);
  r.finish();
  return own;
}

std::vector<kinematics::Contact> contacts_of(Reader& body, Errors& errors, std::size_t max_count,
                                             bool required = true) {
  std::vector<kinematics::Contact> out;
  const json* list = array(body, "contacts", required, max_count);
  if (!list) return out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    Reader r((*list)[i], "/contacts/" + std::to_string(i), errors);
    kinematics::Contact c;
    r.number("x_m", c.x_m, -kMaxCoordinateM, kMaxCoordinateM, true);
    r.number("y_m", c.y_m, -kMaxCoordinateM, kMaxCoordinateM, true);
    r.number("course_deg", c.course_deg, -360.0, 360.0, true);
    r.number("speed_mps", c.speed_mps, 0.0, kMaxContactSpeedMps, true);
    r.finish();
    out.push_back(c);
  }
  return out;
}

template <class T>
app::Result<T> checked(T value, const Errors& errors) {
  if (errors.empty()) return value;
  app::Error e = app::invalid_argument(errors.front().field, errors.front().message);
  for (const auto& f : errors)
    e.fields.push_back({f.field, f.message});
  return e;
}

}  // namespace

app::Result<ManeuverRequest> maneuver_request(const json& body, const std::string& vehicle_id) {
  Errors errors;
  ManeuverRequest out;
  app::ManeuverQuery& q = out.query;
  q.vehicle_id = vehicle_id;
  Reader r(body, "", errors);
  const Own own = own_of(r, errors);
  q.own = own.pose;
  q.speed_mps = own.speed_mps;
  // With the station's live contacts, a request may name none of its own.
  q.live_contacts = boolean(r, "live_contacts").value_or(false);
  q.contacts = contacts_of(r, errors, kMaxManeuverContacts, !q.live_contacts);
  q.standoff_m = number(r, "standoff_m", 0.0, 1000.0, false, true).value_or(q.standoff_m);
  q.horizon_s =
      number(r, "horizon_s", 0.0, kMaxManeuverHorizonS, false, true).value_or(q.horizon_s);
  if (const json* list = array(r, "candidates_deg", false, kMaxManeuverCandidates)) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const json& d = (*list)[i];
      if (d.is_number() && std::abs(d.get<double>()) <= 180.0)
        q.candidates_deg.push_back(d.get<double>());
      else
        r.error("/candidates_deg/" + std::to_string(i), "expected a heading change in [-180, 180]");
    }
  }
  if (const auto step = number(r, "candidate_step_deg", 0.5, 180.0, false)) {
    if (!q.candidates_deg.empty())
      r.error("/candidate_step_deg", "give candidates_deg or candidate_step_deg, not both");
    q.candidate_step_deg = *step;
  }
  q.candidate_speed_mps = number(r, "candidate_speed_mps", 0.0, kMaxSpeedMps, false, true);
  q.method = method(r, "method").value_or(q.method);
  q.model_id = id(r, "model_id");
  q.corridor_share = number(r, "corridor", 0.5, 0.999, false).value_or(q.corridor_share);
  q.use_corridor = boolean(r, "use_corridor").value_or(q.use_corridor);
  // "current": "live" (the station's estimate), "none" (through the water) or
  // {"east_mps": E, "north_mps": N}; absent: over ground wherever the station knows the current.
  if (const json* c = present(r, "current", false)) {
    if (c->is_string() && c->get<std::string>() == "live") {
      q.live_current = true;
    } else if (c->is_string() && c->get<std::string>() == "none") {
      q.no_current = true;
    } else if (c->is_object() && c->size() == 2 && c->contains("east_mps") &&
               c->contains("north_mps") && (*c)["east_mps"].is_number() &&
               (*c)["north_mps"].is_number()) {
      q.current =
          kinematics::WaterCurrent{(*c)["east_mps"].get<double>(), (*c)["north_mps"].get<double>()};
    } else {
      r.error("/current", R"(expected "live", "none" or {"east_mps": E, "north_mps": N} (m/s))");
    }
  }
  if (const auto ref = speed_reference(r, "speed_reference")) q.speed_over_ground = *ref;
  q.max_risk = number(r, "max_risk", 0.0, 1.0, false).value_or(q.max_risk);
  q.prefer_starboard = boolean(r, "colregs").value_or(q.prefer_starboard);
  if (const json* rule = present(r, "rule", false)) {
    if (rule->is_string() && (*rule == "risk" || *rule == "corridor"))
      q.corridor_rule = *rule == "corridor";
    else
      r.error("/rule", R"(expected "risk" or "corridor")");
  }
  q.initial_yaw_rate_dps = number(r, "initial_yaw_rate_dps", -90.0, 90.0, false);
  out.path_step_s = number(r, "path_step_s", 0.0, 60.0, false).value_or(out.path_step_s);
  r.finish();
  return checked(std::move(out), errors);
}

app::Result<SimulateRequest> simulate_request(const json& body) {
  Errors errors;
  SimulateRequest out;
  app::SimulatedManeuverQuery& q = out.query;
  Reader r(body, "", errors);
  const Own own = own_of(r, errors);
  out.own_position = {own.pose.x_m, own.pose.y_m};
  q.own_heading_deg = own.pose.heading_deg;
  q.own_speed_mps = own.speed_mps;
  // The simulator's own vehicle starts at the origin: the contacts are moved with it.
  q.contacts = contacts_of(r, errors, kMaxSimulatedContacts);
  for (auto& c : q.contacts) {
    c.x_m -= own.pose.x_m;
    c.y_m -= own.pose.y_m;
  }
  r.number("dheading_deg", q.dheading_deg, -180.0, 180.0, true);
  q.speed_mps = number(r, "speed_mps", 0.0, kMaxSpeedMps, false, true);
  r.number("horizon_s", q.horizon_s, 0.0, kMaxSimulatedHorizonS, false, true);
  if (const json* seed = present(r, "seed", false)) {
    if (seed->is_number_unsigned())
      q.seed = seed->get<std::uint64_t>();
    else
      r.error("/seed", "expected a whole number >= 0");
  }
  out.standoff_m = number(r, "standoff_m", 0.0, 1000.0, false, true);
  out.path_step_s = number(r, "path_step_s", 0.0, 60.0, false).value_or(out.path_step_s);
  r.finish();
  return checked(std::move(out), errors);
}

app::OngoingQuery ongoing_query(const ApiRequest& r, const std::string& vehicle_id) {
  app::OngoingQuery q;
  q.vehicle_id = vehicle_id;
  q.start.x_m = required_number(r, "x", -kMaxCoordinateM, kMaxCoordinateM);
  q.start.y_m = required_number(r, "y", -kMaxCoordinateM, kMaxCoordinateM);
  q.start.heading_deg = required_number(r, "heading", -360.0, 720.0);
  q.dheading_deg = required_number(r, "dheading", -180.0, 180.0);
  q.speed_mps = required_number(r, "speed", 0.0, kMaxSpeedMps);
  if (!(q.speed_mps > 0.0)) throw bad_parameter("speed", "must be > 0");
  q.elapsed_s = required_number(r, "elapsed", 0.0, kMaxManeuverHorizonS);
  const auto mx = number_param(r, "mx", -kMaxCoordinateM, kMaxCoordinateM);
  const auto my = number_param(r, "my", -kMaxCoordinateM, kMaxCoordinateM);
  if (mx.has_value() != my.has_value())
    throw bad_parameter(mx ? "my" : "mx", "a measured position needs mx and my");
  if (mx) q.measured = kinematics::Point{*mx, *my};
  q.method = method_param(r).value_or(q.method);
  q.model_id = id_param(r, "model");
  q.corridor_share = number_param(r, "corridor", 0.5, 0.999).value_or(q.corridor_share);
  q.horizon_s = number_param(r, "horizon", 1.0, kMaxManeuverHorizonS).value_or(q.horizon_s);
  const CurrentParam current = current_param(r);
  q.current = current.current;
  q.live_current = current.live;
  q.no_current = current.none;
  q.speed_over_ground = speed_reference_param(r);
  return q;
}

}  // namespace avk::server
