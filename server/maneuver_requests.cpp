#include "server/maneuver_requests.hpp"

#include <cmath>
#include <set>
#include <vector>

#include "kinematics/json_parse.hpp"
#include "server/api_params.hpp"
#include "server/serialize.hpp"

namespace avk::server {

using nlohmann::json;

namespace {

// Reads the members of one object of a request, recording every problem under its JSON pointer;
// finish() reports the members nobody asked for.
class Fields {
 public:
  Fields(const json& obj, std::string pointer, std::vector<app::FieldError>& errors)
      : obj_(obj), pointer_(std::move(pointer)), errors_(errors) {
    ok_ = obj.is_object();
    if (!ok_) error(pointer_.empty() ? "/" : pointer_, "must be an object");
  }
  Fields(const Fields&) = delete;
  Fields& operator=(const Fields&) = delete;
  ~Fields() {
    if (!ok_) return;
    for (const auto& [key, value] : obj_.items())
      if (!known_.count(key))
        error(pointer_ + kinematics::json_member_pointer(key), "is not a known field");
  }

  std::string at(const char* key) const { return pointer_ + "/" + key; }
  // Where the problems go, for the nested objects read with their own Fields.
  std::vector<app::FieldError>& errors() { return errors_; }
  void error(const std::string& pointer, const std::string& message) {
    errors_.push_back({pointer, message});
  }

  const json* get(const char* key, bool required) {
    known_.insert(key);
    if (!ok_) return nullptr;
    const auto it = obj_.find(key);
    if (it == obj_.end() || it->is_null()) {
      if (required) error(at(key), "is missing");
      return nullptr;
    }
    return &*it;
  }

  // A finite number in [min, max] (or (min, max] when min_exclusive).
  std::optional<double> number(const char* key, double min, double max, bool required,
                               bool min_exclusive = false) {
    const json* v = get(key, required);
    return v ? number_value(*v, at(key), min, max, min_exclusive) : std::nullopt;
  }

  std::optional<double> number_value(const json& v, const std::string& pointer, double min,
                                     double max, bool min_exclusive = false) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      error(pointer, "must be a number, got " + describe_value(v));
      return std::nullopt;
    }
    const double d = v.get<double>();
    if (d < min || d > max || (min_exclusive && d == min)) {
      error(pointer, std::string("must be in ") + (min_exclusive ? "(" : "[") + num(min) + ", " +
                         num(max) + "], got " + num(d));
      return std::nullopt;
    }
    return d;
  }

  std::optional<bool> boolean(const char* key) {
    const json* v = get(key, false);
    if (!v) return std::nullopt;
    if (!v->is_boolean()) {
      error(at(key), "must be true or false");
      return std::nullopt;
    }
    return v->get<bool>();
  }

  std::optional<app::PredictionMethod> method(const char* key) {
    const json* v = get(key, false);
    if (!v) return std::nullopt;
    const auto m =
        v->is_string() ? app::prediction_method_from_string(v->get<std::string>()) : std::nullopt;
    if (!m) error(at(key), "must be avk, model or instantaneous");
    return m;
  }

  std::optional<std::int64_t> id(const char* key) {
    const json* v = get(key, false);
    if (!v) return std::nullopt;
    if (!v->is_number_integer() || v->get<std::int64_t>() <= 0) {
      error(at(key), "must be a positive whole number, got " + describe_value(*v));
      return std::nullopt;
    }
    return v->get<std::int64_t>();
  }

  // An array of at least one and at most max_count elements.
  const json* array(const char* key, bool required, std::size_t max_count) {
    const json* v = get(key, required);
    if (!v) return nullptr;
    if (!v->is_array() || v->empty()) {
      error(at(key), "must be a non-empty array");
      return nullptr;
    }
    if (v->size() > max_count) {
      error(at(key), "holds " + std::to_string(v->size()) + " elements, at most " +
                         std::to_string(max_count) + " are taken");
      return nullptr;
    }
    return v;
  }

 private:
  const json& obj_;
  std::string pointer_;
  std::vector<app::FieldError>& errors_;
  std::set<std::string> known_;
  bool ok_ = true;
};

constexpr double kMaxCoordinateM = 1e6;
constexpr double kMaxSpeedMps = 20.0;  // own vehicle; the station's vehicles are small
constexpr double kMaxContactSpeedMps = 50.0;

struct Own {
  kinematics::Pose pose;
  double speed_mps = 1.0;
};

Own own_of(Fields& body) {
  Own own;
  const json* v = body.get("own", true);
  if (!v) return own;
  Fields f(*v, "/own", body.errors());
  own.pose.x_m = f.number("x_m", -kMaxCoordinateM, kMaxCoordinateM, false).value_or(0.0);
  own.pose.y_m = f.number("y_m", -kMaxCoordinateM, kMaxCoordinateM, false).value_or(0.0);
  own.pose.heading_deg = f.number("heading_deg", -360.0, 360.0, true).value_or(0.0);
  own.speed_mps = f.number("speed_mps", 0.0, kMaxSpeedMps, true, true).value_or(1.0);
  return own;
}

std::vector<kinematics::Contact> contacts_of(Fields& body, std::size_t max_count) {
  std::vector<kinematics::Contact> out;
  const json* list = body.array("contacts", true, max_count);
  if (!list) return out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    Fields f((*list)[i], "/contacts/" + std::to_string(i), body.errors());
    kinematics::Contact c;
    c.x_m = f.number("x_m", -kMaxCoordinateM, kMaxCoordinateM, true).value_or(0.0);
    c.y_m = f.number("y_m", -kMaxCoordinateM, kMaxCoordinateM, true).value_or(0.0);
    c.course_deg = f.number("course_deg", -360.0, 360.0, true).value_or(0.0);
    c.speed_mps = f.number("speed_mps", 0.0, kMaxContactSpeedMps, true).value_or(0.0);
    out.push_back(c);
  }
  return out;
}

template <class T>
app::Result<T> checked(T value, const std::vector<app::FieldError>& errors) {
  if (errors.empty()) return value;
  const app::FieldError& first = errors.front();
  app::Error e = app::invalid_argument(first.field, first.message);
  e.fields = errors;
  return e;
}

}  // namespace

app::Result<ManeuverRequest> maneuver_request(const json& body, const std::string& vehicle_id) {
  std::vector<app::FieldError> errors;
  ManeuverRequest out;
  app::ManeuverQuery& q = out.query;
  q.vehicle_id = vehicle_id;
  {
    Fields f(body, "", errors);
    const Own own = own_of(f);
    q.own = own.pose;
    q.speed_mps = own.speed_mps;
    q.contacts = contacts_of(f, kMaxManeuverContacts);
    q.standoff_m = f.number("standoff_m", 0.0, 1000.0, false, true).value_or(q.standoff_m);
    q.horizon_s =
        f.number("horizon_s", 0.0, kMaxManeuverHorizonS, false, true).value_or(q.horizon_s);
    if (const json* list = f.array("candidates_deg", false, kMaxManeuverCandidates)) {
      for (std::size_t i = 0; i < list->size(); ++i)
        if (const auto d =
                f.number_value((*list)[i], "/candidates_deg/" + std::to_string(i), -180.0, 180.0))
          q.candidates_deg.push_back(*d);
    }
    if (const auto step = f.number("candidate_step_deg", 0.5, 180.0, false)) {
      if (body.contains("candidates_deg"))
        f.error("/candidate_step_deg", "give candidates_deg or candidate_step_deg, not both");
      q.candidate_step_deg = *step;
    }
    q.candidate_speed_mps = f.number("candidate_speed_mps", 0.0, kMaxSpeedMps, false, true);
    q.method = f.method("method").value_or(q.method);
    q.model_id = f.id("model_id");
    q.corridor_share = f.number("corridor", 0.5, 0.999, false).value_or(q.corridor_share);
    q.use_corridor = f.boolean("use_corridor").value_or(q.use_corridor);
    out.path_step_s = f.number("path_step_s", 0.0, 60.0, false).value_or(out.path_step_s);
  }
  return checked(std::move(out), errors);
}

app::Result<SimulateRequest> simulate_request(const json& body) {
  std::vector<app::FieldError> errors;
  SimulateRequest out;
  app::SimulatedManeuverQuery& q = out.query;
  {
    Fields f(body, "", errors);
    const Own own = own_of(f);
    out.own_position = {own.pose.x_m, own.pose.y_m};
    q.own_heading_deg = own.pose.heading_deg;
    q.own_speed_mps = own.speed_mps;
    // The simulator's own vehicle starts at the origin: the contacts are moved with it.
    q.contacts = contacts_of(f, kMaxSimulatedContacts);
    for (auto& c : q.contacts) {
      c.x_m -= own.pose.x_m;
      c.y_m -= own.pose.y_m;
    }
    q.dheading_deg = f.number("dheading_deg", -180.0, 180.0, true).value_or(0.0);
    q.speed_mps = f.number("speed_mps", 0.0, kMaxSpeedMps, false, true);
    q.horizon_s =
        f.number("horizon_s", 0.0, kMaxSimulatedHorizonS, false, true).value_or(q.horizon_s);
    if (const json* seed = f.get("seed", false)) {
      if (seed->is_number_unsigned())
        q.seed = seed->get<std::uint64_t>();
      else
        f.error("/seed", "must be a whole number >= 0");
    }
    out.standoff_m = f.number("standoff_m", 0.0, 1000.0, false, true);
    out.path_step_s = f.number("path_step_s", 0.0, 60.0, false).value_or(out.path_step_s);
  }
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
  return q;
}

}  // namespace avk::server
