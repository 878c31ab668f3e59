#include "app/foxglove/messages.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "app/foxglove/channels.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/polygon_inset.hpp"

namespace avk::app::foxglove {

using nlohmann::json;

namespace {

constexpr double kNsPerS = 1e9;

json timestamp(double t_s) {
  const std::uint64_t ns = to_ns(t_s);
  return {{"sec", ns / 1'000'000'000ULL}, {"nsec", ns % 1'000'000'000ULL}};
}

json vec3(double x, double y, double z = 0.0) {
  return {{"x", x}, {"y", y}, {"z", z}};
}

json quaternion_json(const Quaternion& q) {
  return {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}};
}

json identity_pose() {
  return {{"position", vec3(0, 0)}, {"orientation", quaternion_json({})}};
}

json optional_number(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

struct Rgba {
  double r, g, b, a;
};
json color(const Rgba& c) {
  return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}};
}

// The dashboard's colours (web/css/app.css), so a viewer and the page agree on what is what.
constexpr Rgba kMeasured{0.10, 0.10, 0.10, 1.0};
constexpr Rgba kAvk{0.12, 0.47, 0.71, 1.0};
constexpr Rgba kAvkCorridor{0.12, 0.47, 0.71, 0.45};
constexpr Rgba kModel{1.00, 0.50, 0.05, 1.0};
constexpr Rgba kInstantaneous{0.84, 0.15, 0.16, 1.0};
constexpr Rgba kGoal{0.40, 0.40, 0.40, 0.8};
constexpr Rgba kRegion{0.17, 0.63, 0.17, 1.0};
constexpr Rgba kBuffer{0.74, 0.74, 0.13, 1.0};

Rgba method_color(const std::string& method) {
  if (method == "avk") return kAvk;
  if (method == "model") return kModel;
  return kInstantaneous;
}

enum class LineType { strip = 0, loop = 1 };

json line(const kinematics::Polyline& points, const Rgba& c, double thickness_px,
          LineType type = LineType::strip) {
  json pts = json::array();
  for (const auto& p : points)
    pts.push_back(vec3(p.x_m, p.y_m));
  // Thickness in pixels (scale_invariant): lines stay readable at any zoom of the 3D panel.
  return {{"type", static_cast<int>(type)}, {"pose", identity_pose()},  {"thickness", thickness_px},
          {"scale_invariant", true},        {"points", std::move(pts)}, {"color", color(c)},
          {"colors", json::array()},        {"indices", json::array()}};
}

json text(const kinematics::Point& at, const std::string& s, const Rgba& c) {
  return {{"pose", {{"position", vec3(at.x_m, at.y_m, 1.0)}, {"orientation", quaternion_json({})}}},
          {"billboard", true},
          {"font_size", 14.0},
          {"scale_invariant", true},
          {"color", color(c)},
          {"text", s}};
}

json entity(double t_s, const std::string& id, json lines, json texts = json::array(),
            json metadata = json::array()) {
  return {{"timestamp", timestamp(t_s)},
          {"frame_id", kGridFrame},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},  // until replaced
          {"frame_locked", false},
          {"metadata", std::move(metadata)},
          {"arrows", json::array()},
          {"cubes", json::array()},
          {"spheres", json::array()},
          {"cylinders", json::array()},
          {"lines", std::move(lines)},
          {"triangles", json::array()},
          {"texts", std::move(texts)},
          {"models", json::array()}};
}

json key_value(const std::string& k, const std::string& v) {
  return {{"key", k}, {"value", v}};
}

// A goal heading as a ray from the turn's start, long enough to read at a turn's scale.
kinematics::Polyline goal_ray(const kinematics::Pose& start, double heading_deg, double length_m) {
  const double h = kinematics::deg_to_rad(heading_deg);
  return {{start.x_m, start.y_m},
          {start.x_m + length_m * std::sin(h), start.y_m + length_m * std::cos(h)}};
}

std::string dump(const json& j) {
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

json log_json(double t_s, LogLevel level, const std::string& name, const std::string& message) {
  return {{"timestamp", timestamp(t_s)},
          {"level", static_cast<int>(level)},
          {"message", message},
          {"name", name},
          {"file", ""},
          {"line", 0}};
}

}  // namespace

std::uint64_t to_ns(double t_s) {
  if (!(t_s > 0.0)) return 0;
  return static_cast<std::uint64_t>(std::llround(t_s * kNsPerS));
}

double to_s(std::uint64_t t_ns) {
  return static_cast<double>(t_ns) / kNsPerS;
}

Quaternion heading_quaternion(double heading_deg) {
  const double yaw = kinematics::deg_to_rad(90.0 - heading_deg);
  return {0.0, 0.0, std::sin(yaw / 2.0), std::cos(yaw / 2.0)};
}

std::string pose_message(const NavigationState& s) {
  return dump({{"timestamp", timestamp(s.t_s)},
               {"frame_id", kGridFrame},
               {"pose",
                {{"position", vec3(s.x_m, s.y_m)},
                 {"orientation", quaternion_json(heading_quaternion(s.heading_deg))}}}});
}

std::string transform_message(const NavigationState& s, const std::string& vehicle_id) {
  return dump({{"timestamp", timestamp(s.t_s)},
               {"parent_frame_id", kGridFrame},
               {"child_frame_id", vehicle_frame(vehicle_id)},
               {"translation", vec3(s.x_m, s.y_m)},
               {"rotation", quaternion_json(heading_quaternion(s.heading_deg))}});
}

std::string location_message(const NavigationState& s, const std::string& vehicle_id) {
  const vehicle::LatLon p = s.position.value_or(vehicle::LatLon{});
  // The station knows no covariance of a fix: type UNKNOWN (0) with zeros, as the schema asks.
  return dump({{"timestamp", timestamp(s.t_s)},
               {"frame_id", vehicle_frame(vehicle_id)},
               {"latitude", p.lat_deg},
               {"longitude", p.lon_deg},
               {"altitude", 0.0},
               {"position_covariance", json::array({0, 0, 0, 0, 0, 0, 0, 0, 0})},
               {"position_covariance_type", 0}});
}

std::string navigation_message(const NavigationState& s) {
  return dump({{"timestamp", timestamp(s.t_s)},
               {"t_s", s.t_s},
               {"x_m", s.x_m},
               {"y_m", s.y_m},
               {"heading_deg", s.heading_deg},
               {"desired_heading_deg", optional_number(s.desired_heading_deg)},
               {"speed_mps", s.speed_mps},
               {"desired_speed_mps", optional_number(s.desired_speed_mps)},
               {"yaw_rate_dps", optional_number(s.yaw_rate_dps)},
               {"helm_mode", s.helm_mode ? json(*s.helm_mode) : json()},
               {"mission_id", s.mission_id ? json(*s.mission_id) : json()}});
}

std::string log_message(double t_s, LogLevel level, const std::string& name,
                        const std::string& message) {
  return dump(log_json(t_s, level, name, message));
}

std::string event_log_message(double t_s, LogLevel level, const std::string& vehicle_id,
                              const std::string& kind, const std::string& message) {
  json j = log_json(t_s, level, vehicle_id + "/" + kind, message);
  j["t_s"] = t_s;
  j["kind"] = kind;
  return dump(j);
}

std::string turn_scene_message(const TurnScene& scene) {
  json entities = json::array();
  const double reach_m = 30.0;
  entities.push_back(entity(
      scene.t_s, "turn/goal",
      json::array({line(goal_ray(scene.start, scene.goal_heading_deg, reach_m), kGoal, 1.0)})));
  for (const auto& p : scene.predictions) {
    json lines = json::array({line(p.trajectory, method_color(p.method), 2.0)});
    if (p.corridor) {
      lines.push_back(line(p.corridor->left, kAvkCorridor, 1.0));
      lines.push_back(line(p.corridor->right, kAvkCorridor, 1.0));
    }
    json metadata = json::array({key_value("method", p.method)});
    if (!p.frame.empty()) metadata.push_back(key_value("frame", p.frame));
    if (!p.current.empty()) metadata.push_back(key_value("current", p.current));
    entities.push_back(entity(scene.t_s, "turn/" + p.method, std::move(lines), json::array(),
                              std::move(metadata)));
  }
  if (!scene.measured.empty())
    entities.push_back(
        entity(scene.t_s, "turn/measured", json::array({line(scene.measured, kMeasured, 2.5)})));
  std::string label = scene.cell_label.value_or("no CKT cell");
  json cell_metadata = json::array({key_value("state", scene.state),
                                    key_value("speed_mps", json(scene.speed_mps).dump()),
                                    key_value("dheading_deg", json(scene.dheading_deg).dump())});
  // Every prediction of a scene is asked the same way, so the first says what they move against.
  if (!scene.predictions.empty() && !scene.predictions.front().frame.empty()) {
    const ScenePrediction& p = scene.predictions.front();
    label += p.frame == "ground" ? ", predicted over ground" : ", predicted through the water";
    cell_metadata.push_back(key_value("frame", p.frame));
    if (!p.current.empty()) cell_metadata.push_back(key_value("current", p.current));
  }
  entities.push_back(entity(scene.t_s, "turn/cell", json::array(),
                            json::array({text({scene.start.x_m, scene.start.y_m},
                                              label + " — " + scene.state, kMeasured)}),
                            std::move(cell_metadata)));
  // Entities of the previous turn that this one lacks (a prediction that failed) must not linger.
  json deletions =
      json::array({{{"timestamp", timestamp(scene.t_s)}, {"type", 1}, {"id", ""}}});  // 1: ALL
  return dump({{"deletions", std::move(deletions)}, {"entities", std::move(entities)}});
}

std::string region_scene_message(double t_s, const mission::OperatingRegion& region) {
  json lines = json::array({line(region.polygon, kRegion, 2.0, LineType::loop)});
  const auto buffer = kinematics::inset_polygon(region.polygon, region.buffer_m);
  if (!buffer.empty()) lines.push_back(line(buffer, kBuffer, 1.0, LineType::loop));
  json texts = json::array({text(region.return_point, "return point", kRegion)});
  return dump(
      {{"deletions", json::array()},
       {"entities", json::array({entity(
                        t_s, "region", std::move(lines), std::move(texts),
                        json::array({key_value("buffer_m", json(region.buffer_m).dump())}))})}});
}

}  // namespace avk::app::foxglove
