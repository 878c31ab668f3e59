#include "mission/mission_config.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "kinematics/ckt.hpp"
#include "kinematics/json_parse.hpp"
#include "mission/document_reader.hpp"

namespace avk::mission {

using nlohmann::json;

const char* to_string(DirectionPolicy p) {
  switch (p) {
    case DirectionPolicy::right:
      return "right";
    case DirectionPolicy::left:
      return "left";
    case DirectionPolicy::alternate:
      return "alternate";
    case DirectionPolicy::automatic:
      return "auto";
  }
  return "?";
}

const char* to_string(YawRateMethod m) {
  switch (m) {
    case YawRateMethod::least_squares:
      return "least_squares";
    case YawRateMethod::moving_average:
      return "moving_average";
  }
  return "?";
}

namespace {

std::string describe(const std::vector<FieldError>& errors) {
  std::string s = "invalid mission:";
  for (const auto& e : errors)
    s += "\n  " + e.field + ": " + e.message;
  return s;
}

using Reader = DocumentReader;

std::vector<double> number_list(Reader& r, const char* key, double min, double max,
                                bool min_exclusive, const std::string& unit, std::size_t max_count,
                                double min_spacing) {
  std::vector<double> out;
  const json* v = r.get(key, true);
  if (!v) return out;
  if (!v->is_array() || v->empty()) {
    r.error(r.at(key), "expected a non-empty array of " + unit);
    return out;
  }
  if (v->size() > max_count) {
    // One error, not one per element: the list is refused whole.
    r.error(r.at(key),
            "at most " + std::to_string(max_count) + " values, got " + std::to_string(v->size()));
    return out;
  }
  for (std::size_t i = 0; i < v->size(); ++i) {
    const json& e = (*v)[i];
    const std::string f = r.at(key) + "/" + std::to_string(i);
    if (!e.is_number() || !std::isfinite(e.get<double>())) {
      r.error(f, "expected a number (" + unit + ")");
      continue;
    }
    const double d = e.get<double>();
    if (d < min || d > max || (min_exclusive && d == min)) {
      r.error(f, std::string("must be in ") + (min_exclusive ? "(" : "[") + json(min).dump() +
                     ", " + json(max).dump() + "] " + unit + ", got " + json(d).dump());
      continue;
    }
    // A value within the table's cell tolerance of an earlier one collects the same cell twice
    // and makes the resumed count of a cell ambiguous; one exactly the spacing apart is another
    // cell (the comparison the cells are matched with, mission/turn_plan.hpp).
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (kinematics::within_match(out[j], d, min_spacing)) {
        r.error(f, "duplicates an earlier value (" + json(out[j]).dump() + " " + unit +
                       "; values must be at least " + json(min_spacing).dump() + " " + unit +
                       " apart)");
        break;
      }
    }
    out.push_back(d);
  }
  return out;
}

// turn_array.speed_changes: [{"from_mps": u0, "to_mps": u1}, ...].
std::vector<SpeedChange> speed_change_list(Reader& r, double vmax) {
  std::vector<SpeedChange> out;
  const json* v = r.get("speed_changes", false);
  if (!v) return out;
  const std::string field = r.at("speed_changes");
  if (!v->is_array() || v->empty()) {
    r.error(field, "expected a non-empty array of {\"from_mps\", \"to_mps\"} objects");
    return out;
  }
  if (v->size() > kMaxMissionSpeedChanges) {
    r.error(field, "at most " + std::to_string(kMaxMissionSpeedChanges) + " entries, got " +
                       std::to_string(v->size()));
    return out;
  }
  std::vector<FieldError> entry_errors;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string f = field + "/" + std::to_string(i);
    std::vector<FieldError> errors;
    Reader e((*v)[i], f, errors);
    SpeedChange c;
    e.number("from_mps", c.from_mps, 0.0, vmax, true, true);
    e.number("to_mps", c.to_mps, 0.0, vmax, true, true);
    e.finish();
    if (errors.empty() && kinematics::within_match(c.from_mps, c.to_mps, kMinSpeedSpacingMps)) {
      errors.push_back({f + "/to_mps", "must differ from from_mps by at least " +
                                           json(kMinSpeedSpacingMps).dump() +
                                           " m/s (a constant-speed turn belongs in speeds_mps)"});
    }
    for (std::size_t j = 0; errors.empty() && j < out.size(); ++j) {
      if (kinematics::within_match(out[j].from_mps, c.from_mps, kMinSpeedSpacingMps) &&
          kinematics::within_match(out[j].to_mps, c.to_mps, kMinSpeedSpacingMps)) {
        errors.push_back({f, "duplicates entry " + std::to_string(j)});
      }
    }
    for (auto& err : errors)
      r.error(err.field, err.message);
    if (errors.empty()) out.push_back(c);
  }
  return out;
}

}  // namespace

double return_speed_mps(const MissionConfig& config) {
  if (config.region.return_speed_mps) return *config.region.return_speed_mps;
  if (config.excitation) return config.excitation->speed_mps;
  if (!config.turn_array.speeds_mps.empty()) return config.turn_array.speeds_mps.front();
  if (!config.turn_array.speed_changes.empty())
    return config.turn_array.speed_changes.front().from_mps;
  return 1.0;
}

MissionConfigError::MissionConfigError(std::vector<FieldError> errors)
    : std::runtime_error(describe(errors)), errors_(std::move(errors)) {}

MissionConfig parse_mission_config(std::string_view json_text, double max_speed_mps) {
  std::vector<FieldError> errors;
  json doc;
  try {
    doc = kinematics::parse_json_bounded(json_text);
  } catch (const kinematics::JsonSyntaxError& e) {
    // A number too large for a double is reported against its field, like any bad value.
    throw MissionConfigError(
        {{e.number_out_of_range() ? e.pointer() : std::string("json"),
          e.number_out_of_range() ? e.reason()
                                  : "not valid JSON at byte " + std::to_string(e.position()) +
                                        " (line " + std::to_string(e.line()) + " column " +
                                        std::to_string(e.column()) + "): " + e.reason()}});
  } catch (const kinematics::ParseError& e) {
    throw MissionConfigError({{e.field(), e.message()}});
  }
  MissionConfig c;
  Reader root(doc, "", errors);
  root.text("name", c.name, true, kMaxMissionNameBytes);
  if (const json* kind = root.get("kind", false)) {
    if (*kind == "turns") {
      c.kind = MissionKind::turns;
    } else if (*kind == "persistent_excitation") {
      c.kind = MissionKind::persistent_excitation;
    } else {
      root.error("/kind", "must be 'turns' or 'persistent_excitation'");
    }
  }
  const double vmax = max_speed_mps;
  if (const json* ta = root.get("turn_array", c.kind == MissionKind::turns)) {
    Reader r(*ta, "/turn_array", errors);
    if (r.ok()) {
      c.turn_array.speed_changes = speed_change_list(r, vmax);
      // With speed changes the constant-speed axis may be left out.
      const bool speeds_required = !(ta->is_object() && ta->contains("speed_changes"));
      if (speeds_required || ta->contains("speeds_mps")) {
        c.turn_array.speeds_mps = number_list(r, "speeds_mps", 0.0, vmax, true, "m/s",
                                              kMaxMissionSpeeds, kMinSpeedSpacingMps);
      }
      c.turn_array.dheadings_deg = number_list(r, "dheadings_deg", 0.0, 180.0, true, "deg",
                                               kMaxMissionDheadings, kMinDheadingSpacingDeg);
      if (const json* d = r.get("direction", false)) {
        if (*d == "right") {
          c.turn_array.direction = DirectionPolicy::right;
        } else if (*d == "left") {
          c.turn_array.direction = DirectionPolicy::left;
        } else if (*d == "alternate") {
          c.turn_array.direction = DirectionPolicy::alternate;
        } else if (*d == "auto") {
          c.turn_array.direction = DirectionPolicy::automatic;
        } else {
          r.error("/turn_array/direction", "must be right, left, alternate or auto");
        }
      }
      r.integer("repeats", c.turn_array.repeats, 1, kMaxMissionRepeats);
      r.integer("max_attempts", c.turn_array.max_attempts, 1, 1000);
      if (ta->is_object() && ta->contains("initial_yaw_rates_dps")) {
        c.turn_array.initial_yaw_rates_dps =
            number_list(r, "initial_yaw_rates_dps", -kMaxInitialYawRateDps, kMaxInitialYawRateDps,
                        false, "deg/s", kMaxMissionYawRates, kMinYawRateSpacingDps);
      }
      r.number("initial_yaw_rate_band_dps", c.turn_array.initial_yaw_rate_band_dps, 0.0, 20.0,
               false, true);
      r.number("pre_turn_dheading_deg", c.turn_array.pre_turn_dheading_deg, 0.0, 180.0, false,
               true);
      r.number("initial_yaw_rate_timeout_s", c.turn_array.initial_yaw_rate_timeout_s, 0.0, 3600.0,
               false, true);
      r.finish();
      // Each axis is bounded above, so this product cannot overflow.
      const std::size_t planned =
          (c.turn_array.speeds_mps.size() + c.turn_array.speed_changes.size()) *
          c.turn_array.dheadings_deg.size() *
          std::max<std::size_t>(1, c.turn_array.initial_yaw_rates_dps.size()) *
          static_cast<std::size_t>(c.turn_array.repeats);
      if (planned > kMaxPlannedTurns) {
        r.error("/turn_array", "plans " + std::to_string(planned) +
                                   " turns ((speeds + speed changes) x heading changes x initial "
                                   "yaw rates x "
                                   "repeats); at most " +
                                   std::to_string(kMaxPlannedTurns));
      }
    }
  }
  if (const json* cs = root.get("condition_set", false)) {
    Reader r(*cs, "/condition_set", errors);
    r.number("speed_tolerance_mps", c.condition_set.speed_tolerance_mps, 0.0, 1.0, false, true);
    r.number("max_yaw_rate_dps", c.condition_set.max_yaw_rate_dps, 0.0, 90.0, false, true);
    r.integer("window", c.condition_set.window, 1, 100);
    r.number("timeout_s", c.condition_set.timeout_s, 0.0, 3600.0, false, true);
    r.number("max_heading_error_deg", c.condition_set.max_heading_error_deg, 0.0, 180.0, false,
             true);
    if (const json* m = r.get("yaw_rate", false)) {
      if (*m == "least_squares") {
        c.condition_set.yaw_rate_method = YawRateMethod::least_squares;
      } else if (*m == "moving_average") {
        c.condition_set.yaw_rate_method = YawRateMethod::moving_average;
      } else {
        r.error("/condition_set/yaw_rate", "must be least_squares or moving_average");
      }
    }
    r.number("yaw_rate_window_s", c.condition_set.yaw_rate_window_s, 0.0, 60.0, false, true);
    r.number("run_ahead_s", c.condition_set.run_ahead_s, 0.0, 600.0);
    r.finish();
  }
  if (const json* ch = root.get("constant_heading", false)) {
    Reader r(*ch, "/constant_heading", errors);
    r.number("completion_threshold_deg", c.completion.threshold_deg, 0.0, 45.0, false, true);
    r.number("completion_fraction", c.completion.fraction, 0.0, 1.0, false, true);
    r.number("completion_floor_deg", c.completion.floor_deg, 0.0, 45.0, false, true);
    r.number("timeout_s", c.turn_timeout_s, 0.0, 3600.0, false, true);
    // A floor above the threshold is a contradiction in the file, refused rather than guessed
    // at. A threshold alone below the default floor (valid before the floor existed) is not one:
    // the threshold bounds the rule (completion_threshold_deg).
    if (ch->is_object() && ch->contains("completion_floor_deg") &&
        c.completion.floor_deg > c.completion.threshold_deg) {
      r.error("/constant_heading/completion_floor_deg",
              "must be <= completion_threshold_deg (" + json(c.completion.threshold_deg).dump() +
                  "), got " + json(c.completion.floor_deg).dump());
    }
    r.finish();
  }
  if (const json* reg = root.get("operating_region", true)) {
    Reader r(*reg, "/operating_region", errors);
    if (const json* poly = r.get("polygon_m", true)) {
      if (!poly->is_array() || poly->size() < 3) {
        r.error("/operating_region/polygon_m", "expected at least 3 [x_m, y_m] vertices");
      } else if (poly->size() > kMaxRegionVertices) {
        // Refused before any geometry: the simplicity check compares every pair of edges.
        r.error("/operating_region/polygon_m", "at most " + std::to_string(kMaxRegionVertices) +
                                                   " vertices, got " +
                                                   std::to_string(poly->size()));
      } else {
        for (std::size_t i = 0; i < poly->size(); ++i) {
          if (auto p = r.point((*poly)[i], "/operating_region/polygon_m/" + std::to_string(i))) {
            c.region.polygon.push_back(*p);
          }
        }
      }
    }
    r.number("buffer_m", c.region.buffer_m, 0.0, 1000.0);
    double return_speed = 0.0;
    r.number("return_speed_mps", return_speed, 0.0, vmax, false, true);
    if (return_speed > 0.0) c.region.return_speed_mps = return_speed;
    r.number("capture_radius_m", c.region.capture_radius_m, 0.0, 1000.0, false, true);
    bool has_return = false;
    if (const json* rp = r.get("return_point_m", true)) {
      if (auto p = r.point(*rp, "/operating_region/return_point_m")) {
        c.region.return_point = *p;
        has_return = true;
      }
    }
    r.finish();
    const auto& poly = c.region.polygon;
    if (poly.size() >= 3 && reg->contains("polygon_m") &&
        poly.size() == reg->at("polygon_m").size()) {
      const double area = polygon_area_m2(poly);
      double perimeter = 0.0;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        perimeter += kinematics::distance_m(poly[i], poly[(i + 1) % poly.size()]);
      }
      double min_x = poly[0].x_m, max_x = poly[0].x_m, min_y = poly[0].y_m, max_y = poly[0].y_m;
      for (const auto& p : poly) {
        min_x = std::min(min_x, p.x_m);
        max_x = std::max(max_x, p.x_m);
        min_y = std::min(min_y, p.y_m);
        max_y = std::max(max_y, p.y_m);
      }
      if (max_x - min_x > kMaxRegionExtentM || max_y - min_y > kMaxRegionExtentM) {
        r.error("/operating_region/polygon_m",
                "the region spans " + json(std::max(max_x - min_x, max_y - min_y)).dump() +
                    " m; at most " + json(kMaxRegionExtentM).dump() + " m in x and in y");
      } else if (!polygon_is_simple(poly)) {
        r.error("/operating_region/polygon_m", "the polygon intersects itself");
      } else if (area < 400.0) {
        r.error("/operating_region/polygon_m",
                "the region is too small (" + json(area).dump() + " m²; at least 400 m² needed)");
      } else if (c.region.buffer_m >= 2.0 * area / perimeter) {
        // 2A/P is the inradius of a regular shape: a buffer that large leaves no interior.
        r.error("/operating_region/buffer_m", "the buffer leaves no room inside the region");
      } else if (has_return && !point_in_polygon(c.region.return_point, poly)) {
        r.error("/operating_region/return_point_m", "the return point is outside the region");
      }
    }
  }
  if (const json* ex = root.get("excitation", c.kind == MissionKind::persistent_excitation)) {
    Reader r(*ex, "/excitation", errors);
    ExcitationConfig e;
    r.number("speed_mps", e.speed_mps, 0.0, vmax, true, true);
    r.number("duration_s", e.duration_s, 0.0, 86400.0, false, true);
    r.number("min_step_deg", e.min_step_deg, 0.0, 180.0, false, true);
    r.number("max_step_deg", e.max_step_deg, 0.0, 180.0, false, true);
    r.number("min_interval_s", e.min_interval_s, 0.0, 3600.0, false, true);
    r.number("max_interval_s", e.max_interval_s, 0.0, 3600.0, false, true);
    double seed = 1;
    r.number("seed", seed, 0.0, 9007199254740992.0);
    e.seed = static_cast<std::uint64_t>(seed);
    if (e.min_step_deg > e.max_step_deg)
      r.error("/excitation/min_step_deg", "must not exceed max_step_deg");
    if (e.min_interval_s > e.max_interval_s) {
      r.error("/excitation/min_interval_s", "must not exceed max_interval_s");
    }
    r.finish();
    c.excitation = e;
  }
  root.finish();
  if (!errors.empty()) throw MissionConfigError(std::move(errors));
  return c;
}

}  // namespace avk::mission
