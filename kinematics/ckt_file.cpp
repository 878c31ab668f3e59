#include "kinematics/ckt_file.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/json_parse.hpp"
#include "kinematics/parse_error.hpp"

namespace avk::kinematics {

using nlohmann::json;

namespace {

json points_to_json(const Polyline& line) {
  json a = json::array();
  for (const Point& p : line)
    a.push_back({p.x_m, p.y_m});
  return a;
}

json fit_to_json(const CurveFit& f) {
  json j = {
      {"kind", to_string(f.kind)}, {"domain_min", f.domain_min}, {"domain_max", f.domain_max}};
  if (f.kind == FitKind::poly4_xy) {
    j["coefficients"] = f.coefficients;
    j["center"] = f.center;
    j["scale"] = f.scale;
  } else {
    j["knots"] = f.knots;
    j["control_points"] = points_to_json(f.control_points);
  }
  return j;
}

// Reads fields with errors that name the JSON pointer of what is wrong.
class Reader {
 public:
  [[noreturn]] static void fail(const std::string& path, const std::string& what) {
    throw ParseError(path, 0, what);
  }

  static const json& member(const json& obj, const std::string& path, const char* key) {
    if (!obj.is_object()) fail(path, "expected an object");
    const auto it = obj.find(key);
    if (it == obj.end())
      fail(path + "/" + key, std::string("missing required field '") + key + "'");
    return *it;
  }

  static void only_keys(const json& obj, const std::string& path,
                        std::initializer_list<const char*> keys) {
    for (const auto& [k, v] : obj.items()) {
      bool known = false;
      for (const char* allowed : keys)
        known = known || k == allowed;
      if (!known) fail(path + "/" + k, "unknown field '" + k + "'");
    }
  }

  static double number(const json& v, const std::string& path) {
    if (!v.is_number()) fail(path, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path, "expected a finite number");
    return d;
  }

  static double number(const json& obj, const std::string& path, const char* key) {
    return number(member(obj, path, key), path + "/" + key);
  }

  static std::string string(const json& obj, const std::string& path, const char* key) {
    const json& v = member(obj, path, key);
    if (!v.is_string()) fail(path + "/" + key, "expected a string");
    return v.get<std::string>();
  }

  static void bounded_size(const json& v, const std::string& path, std::size_t max) {
    if (v.size() > max)
      fail(path, "at most " + std::to_string(max) + " entries, got " + std::to_string(v.size()));
  }

  static std::vector<double> numbers(const json& v, const std::string& path,
                                     std::size_t max = kCktMaxListLength) {
    if (!v.is_array()) fail(path, "expected an array of numbers");
    bounded_size(v, path, max);
    std::vector<double> out;
    out.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(number(v[i], path + "/" + std::to_string(i)));
    return out;
  }

  static Polyline points(const json& v, const std::string& path) {
    if (!v.is_array()) fail(path, "expected an array of [x_m, y_m] pairs");
    bounded_size(v, path, kCktMaxListLength);
    Polyline out;
    out.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string p = path + "/" + std::to_string(i);
      if (!v[i].is_array() || v[i].size() != 2) fail(p, "expected an [x_m, y_m] pair");
      out.push_back({number(v[i][0], p + "/0"), number(v[i][1], p + "/1")});
    }
    return out;
  }
};

std::vector<double> ascending(const json& v, const std::string& path, std::size_t max) {
  std::vector<double> out = Reader::numbers(v, path, max);
  if (out.empty()) Reader::fail(path, "must not be empty");
  for (std::size_t i = 1; i < out.size(); ++i) {
    if (!(out[i] > out[i - 1]))
      Reader::fail(path + "/" + std::to_string(i), "values must be strictly ascending");
  }
  return out;
}

CurveFit fit_from_json(const json& j, const std::string& path) {
  CurveFit f;
  const std::string kind = Reader::string(j, path, "kind");
  const auto k = fit_kind_from_string(kind);
  if (!k) Reader::fail(path + "/kind", "unknown fit kind '" + kind + "'");
  f.kind = *k;
  f.domain_min = Reader::number(j, path, "domain_min");
  f.domain_max = Reader::number(j, path, "domain_max");
  if (f.kind == FitKind::poly4_xy) {
    Reader::only_keys(j, path,
                      {"kind", "domain_min", "domain_max", "coefficients", "center", "scale"});
    f.coefficients =
        Reader::numbers(Reader::member(j, path, "coefficients"), path + "/coefficients");
    f.center = Reader::number(j, path, "center");
    f.scale = Reader::number(j, path, "scale");
  } else {
    Reader::only_keys(j, path, {"kind", "domain_min", "domain_max", "knots", "control_points"});
    f.knots = Reader::numbers(Reader::member(j, path, "knots"), path + "/knots");
    f.control_points =
        Reader::points(Reader::member(j, path, "control_points"), path + "/control_points");
  }
  try {
    f.check();
  } catch (const std::invalid_argument& e) {
    Reader::fail(path, e.what());
  }
  return f;
}

MeanSd mean_sd_from_json(const json& j, const std::string& path) {
  Reader::only_keys(j, path, {"mean", "sd"});
  MeanSd m{Reader::number(j, path, "mean"), Reader::number(j, path, "sd")};
  if (m.sd < 0.0) Reader::fail(path + "/sd", "standard deviation must not be negative");
  return m;
}

TurnTiming timing_from_json(const json& j, const std::string& path) {
  if (!j.is_object()) Reader::fail(path, "expected an object");
  Reader::only_keys(j, path, {"length_m", "time_s", "time_sd_s"});
  TurnTiming t;
  t.length_m = Reader::number(j, path, "length_m");
  if (!(t.length_m > 0.0)) Reader::fail(path + "/length_m", "must be positive");
  t.time_s = Reader::numbers(Reader::member(j, path, "time_s"), path + "/time_s");
  if (t.time_s.size() != kTimingStations)
    Reader::fail(path + "/time_s", "expected " + std::to_string(kTimingStations) + " values");
  if (t.time_s[0] != 0.0) Reader::fail(path + "/time_s/0", "the first time must be 0");
  for (std::size_t i = 1; i < t.time_s.size(); ++i)
    if (!(t.time_s[i] >= t.time_s[i - 1]))
      Reader::fail(path + "/time_s/" + std::to_string(i), "times must not decrease");
  // The along-track spread is optional: a file written before it was recorded has none.
  if (j.contains("time_sd_s")) {
    t.time_sd_s = Reader::numbers(j["time_sd_s"], path + "/time_sd_s");
    if (t.time_sd_s.size() != kTimingStations)
      Reader::fail(path + "/time_sd_s", "expected " + std::to_string(kTimingStations) + " values");
    for (std::size_t i = 0; i < t.time_sd_s.size(); ++i)
      if (t.time_sd_s[i] < 0.0)
        Reader::fail(path + "/time_sd_s/" + std::to_string(i), "must not be negative");
  }
  return t;
}

}  // namespace

json ckt_to_json(const Ckt& table) {
  json doc;
  doc["format"] = kCktFormatName;
  doc["schema_version"] = kCktSchemaVersion;
  doc["vehicle"] = {{"id", table.vehicle_id}};
  if (table.vehicle_length_m) doc["vehicle"]["length_m"] = *table.vehicle_length_m;
  doc["created_utc"] = table.created_utc;
  doc["frame"] = to_string(table.frame);
  const CktOptions& o = table.options();
  doc["options"] = {
      {"fit_kind", to_string(o.fit_kind)},    {"pwl_epsilon_m", o.pwl_epsilon_m},
      {"mean_x_step_m", o.mean_x_step_m},     {"mean_x_margin_m", o.mean_x_margin_m},
      {"speed_match_mps", o.speed_match_mps}, {"dheading_match_deg", o.dheading_match_deg},
      {"mean_kind", to_string(o.mean_kind)}};
  doc["grid"] = {{"speeds_mps", table.grid().speeds_mps},
                 {"dheadings_deg", table.grid().dheadings_deg}};
  json cells = json::array();
  for (const CktCell& c : table.cells()) {
    if (!c.has_data()) continue;
    json stats = {{"advance_m", {{"mean", c.advance_m.mean}, {"sd", c.advance_m.sd}}},
                  {"transfer_m", {{"mean", c.transfer_m.mean}, {"sd", c.transfer_m.sd}}},
                  {"avk_error_m2", c.avk_error_m2 ? json(*c.avk_error_m2) : json(nullptr)}};
    json cell = {{"speed_mps", c.speed_mps},
                 {"dheading_deg", c.dheading_deg},
                 {"n_turns", c.n_turns},
                 {"stats", std::move(stats)},
                 {"fit", fit_to_json(c.fit)},
                 {"trajectory", points_to_json(c.trajectory)},
                 {"short_of_goal", c.short_of_goal}};
    if (c.corridor) {
      cell["corridor"] = {{"n_turns", c.corridor->n_turns},
                          {"length_m", c.corridor->length_m},
                          {"lateral_sd_m", c.corridor->lateral_sd_m}};
    }
    if (c.timing) {
      cell["timing"] = {{"length_m", c.timing->length_m}, {"time_s", c.timing->time_s}};
      if (!c.timing->time_sd_s.empty()) cell["timing"]["time_sd_s"] = c.timing->time_sd_s;
    }
    cells.push_back(std::move(cell));
  }
  doc["cells"] = std::move(cells);
  return doc;
}

std::string ckt_to_json_string(const Ckt& table) {
  // One top-level field a line and one cell a line: compact, yet a diff shows which cell changed.
  const json doc = ckt_to_json(table);
  std::string out = "{\n";
  bool first = true;
  for (const auto& [key, value] : doc.items()) {
    if (!first) out += ",\n";
    first = false;
    // Appends, not operator+: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    out.append(" ").append(json(key).dump()).append(": ");
    if (key == "cells") {
      out.append("[");
      for (std::size_t i = 0; i < value.size(); ++i) {
        out.append(i ? ",\n  " : "\n  ").append(value[i].dump());
      }
      out.append(value.empty() ? "]" : "\n ]");
    } else {
      out += value.dump();
    }
  }
  return out + "\n}\n";
}

Ckt ckt_from_json(const json& doc) {
  const std::string root;
  if (!doc.is_object()) Reader::fail("/", "the CKT document must be a JSON object");
  Reader::only_keys(doc, root,
                    {"format", "schema_version", "vehicle", "created_utc", "frame", "options",
                     "grid", "cells", "yaw_rate_slices"});
  // The slices are read by yaw_rate_ckt_from_json (ckt3_file.hpp); a 2-D reader skips them.
  if (doc.contains("yaw_rate_slices") && doc["schema_version"].is_number_integer() &&
      doc["schema_version"].get<long long>() < 4)
    Reader::fail("/yaw_rate_slices",
                 "not a field of schema_version " + doc["schema_version"].dump() + " (needs 4)");
  if (Reader::string(doc, root, "format") != kCktFormatName) {
    Reader::fail("/format", std::string("not a CKT file: format must be '") + kCktFormatName + "'");
  }
  const json& version = Reader::member(doc, root, "schema_version");
  if (!version.is_number_integer() || version.get<long long>() < kCktOldestSchemaVersion ||
      version.get<long long>() > kCktSchemaVersion) {
    // The value is quoted only when it is a plain number: a document is the caller's input, and
    // dumping a deeply nested value into a message recurses once per level.
    Reader::fail("/schema_version",
                 "unsupported schema_version" +
                     (version.is_number() ? " " + version.dump() : std::string()) +
                     "; this build reads versions " + std::to_string(kCktOldestSchemaVersion) +
                     " to " + std::to_string(kCktSchemaVersion));
  }
  // A version 1 document has none of the version 2 fields; each is checked where it is read.
  const int schema = static_cast<int>(version.get<long long>());
  const json& vehicle = Reader::member(doc, root, "vehicle");
  Reader::only_keys(vehicle, "/vehicle", {"id", "length_m"});
  std::string vehicle_id = Reader::string(vehicle, "/vehicle", "id");
  std::optional<double> vehicle_length;
  if (vehicle.contains("length_m")) {
    vehicle_length = Reader::number(vehicle, "/vehicle", "length_m");
    if (!(*vehicle_length > 0.0))
      Reader::fail("/vehicle/length_m", "vehicle length must be positive");
  }
  std::string created = Reader::string(doc, root, "created_utc");
  // Tables before schema 4 were all built from turns over ground.
  TableFrame frame = TableFrame::ground;
  if (doc.contains("frame")) {
    if (schema < 4)
      Reader::fail("/frame", "not a field of schema_version " + std::to_string(schema));
    const std::string name = Reader::string(doc, root, "frame");
    const auto f = table_frame_from_string(name);
    if (!f) Reader::fail("/frame", "unknown frame '" + name + "' (ground, water or mixed)");
    frame = *f;
  }

  const json& opts = Reader::member(doc, root, "options");
  Reader::only_keys(opts, "/options",
                    {"fit_kind", "pwl_epsilon_m", "mean_x_step_m", "mean_x_margin_m",
                     "speed_match_mps", "dheading_match_deg", "mean_kind"});
  CktOptions options;
  const std::string fit_kind = Reader::string(opts, "/options", "fit_kind");
  if (!fit_kind_from_string(fit_kind))
    Reader::fail("/options/fit_kind", "unknown fit kind '" + fit_kind + "'");
  options.fit_kind = *fit_kind_from_string(fit_kind);
  options.pwl_epsilon_m = Reader::number(opts, "/options", "pwl_epsilon_m");
  options.mean_x_step_m = Reader::number(opts, "/options", "mean_x_step_m");
  options.mean_x_margin_m = Reader::number(opts, "/options", "mean_x_margin_m");
  options.speed_match_mps = Reader::number(opts, "/options", "speed_match_mps");
  options.dheading_match_deg = Reader::number(opts, "/options", "dheading_match_deg");
  // Version 1 tables were all built on the thesis' x grid.
  options.mean_kind = MeanKind::x_grid;
  if (opts.contains("mean_kind")) {
    if (schema < 2) Reader::fail("/options/mean_kind", "not a field of schema_version 1");
    const std::string kind = Reader::string(opts, "/options", "mean_kind");
    const auto k = mean_kind_from_string(kind);
    if (!k) Reader::fail("/options/mean_kind", "unknown mean kind '" + kind + "'");
    options.mean_kind = *k;
  }

  const json& g = Reader::member(doc, root, "grid");
  Reader::only_keys(g, "/grid", {"speeds_mps", "dheadings_deg"});
  CktGrid grid{
      ascending(Reader::member(g, "/grid", "speeds_mps"), "/grid/speeds_mps", kCktMaxGridSpeeds),
      ascending(Reader::member(g, "/grid", "dheadings_deg"), "/grid/dheadings_deg",
                kCktMaxGridDheadings)};
  for (std::size_t i = 0; i < grid.speeds_mps.size(); ++i) {
    const double u = grid.speeds_mps[i];
    if (!(u > 0.0 && u <= kCktMaxSpeedMps)) {
      Reader::fail("/grid/speeds_mps/" + std::to_string(i),
                   "speed must be in (0, " + json(kCktMaxSpeedMps).dump() + "] m/s");
    }
  }
  for (std::size_t i = 0; i < grid.dheadings_deg.size(); ++i) {
    const double d = grid.dheadings_deg[i];
    if (!(d > 0.0 && d <= 180.0))
      Reader::fail("/grid/dheadings_deg/" + std::to_string(i),
                   "heading change must be in (0, 180]");
  }

  const json& cells_json = Reader::member(doc, root, "cells");
  if (!cells_json.is_array()) Reader::fail("/cells", "expected an array");
  if (cells_json.size() > grid.speeds_mps.size() * grid.dheadings_deg.size()) {
    Reader::fail("/cells", "more cells than the grid has places for");
  }
  std::vector<CktCell> cells;
  std::vector<bool> seen(grid.speeds_mps.size() * grid.dheadings_deg.size(), false);
  for (std::size_t k = 0; k < cells_json.size(); ++k) {
    const std::string path = "/cells/" + std::to_string(k);
    const json& cj = cells_json[k];
    Reader::only_keys(cj, path,
                      {"speed_mps", "dheading_deg", "n_turns", "stats", "fit", "trajectory",
                       "short_of_goal", "corridor", "timing"});
    if (schema < 2 && (cj.contains("short_of_goal") || cj.contains("corridor")))
      Reader::fail(path, "corridor and short_of_goal are not fields of schema_version 1");
    if (schema < 3 && cj.contains("timing"))
      Reader::fail(path + "/timing", "not a field of schema_version " + std::to_string(schema));
    CktCell c;
    c.speed_mps = Reader::number(cj, path, "speed_mps");
    c.dheading_deg = Reader::number(cj, path, "dheading_deg");
    std::size_t si = grid.speeds_mps.size(), di = grid.dheadings_deg.size();
    for (std::size_t i = 0; i < grid.speeds_mps.size(); ++i)
      if (grid.speeds_mps[i] == c.speed_mps) si = i;
    for (std::size_t j = 0; j < grid.dheadings_deg.size(); ++j)
      if (grid.dheadings_deg[j] == c.dheading_deg) di = j;
    if (si == grid.speeds_mps.size()) Reader::fail(path + "/speed_mps", "speed is not on the grid");
    if (di == grid.dheadings_deg.size())
      Reader::fail(path + "/dheading_deg", "heading change is not on the grid");
    if (seen[si * grid.dheadings_deg.size() + di]) Reader::fail(path, "duplicate cell");
    seen[si * grid.dheadings_deg.size() + di] = true;
    const json& n = Reader::member(cj, path, "n_turns");
    if (!n.is_number_unsigned() || n.get<unsigned long long>() == 0) {
      Reader::fail(path + "/n_turns", "expected a positive whole number");
    }
    c.n_turns = n.get<std::size_t>();
    const json& stats = Reader::member(cj, path, "stats");
    Reader::only_keys(stats, path + "/stats", {"advance_m", "transfer_m", "avk_error_m2"});
    c.advance_m = mean_sd_from_json(Reader::member(stats, path + "/stats", "advance_m"),
                                    path + "/stats/advance_m");
    c.transfer_m = mean_sd_from_json(Reader::member(stats, path + "/stats", "transfer_m"),
                                     path + "/stats/transfer_m");
    const json& avk = Reader::member(stats, path + "/stats", "avk_error_m2");
    if (!avk.is_null()) {
      c.avk_error_m2 = Reader::number(avk, path + "/stats/avk_error_m2");
      if (*c.avk_error_m2 < 0.0) Reader::fail(path + "/stats/avk_error_m2", "must not be negative");
    }
    c.fit = fit_from_json(Reader::member(cj, path, "fit"), path + "/fit");
    c.trajectory = Reader::points(Reader::member(cj, path, "trajectory"), path + "/trajectory");
    if (c.trajectory.size() < 2)
      Reader::fail(path + "/trajectory", "a trajectory needs at least 2 vertices");
    if (cj.contains("short_of_goal")) {
      if (!cj["short_of_goal"].is_boolean())
        Reader::fail(path + "/short_of_goal", "expected true or false");
      c.short_of_goal = cj["short_of_goal"].get<bool>();
    }
    if (cj.contains("corridor")) {
      const std::string cp = path + "/corridor";
      const json& co = cj["corridor"];
      if (!co.is_object()) Reader::fail(cp, "expected an object");
      Reader::only_keys(co, cp, {"n_turns", "length_m", "lateral_sd_m"});
      Corridor corridor;
      const json& cn = Reader::member(co, cp, "n_turns");
      if (!cn.is_number_unsigned() || cn.get<unsigned long long>() < 2 ||
          cn.get<unsigned long long>() > c.n_turns)
        Reader::fail(cp + "/n_turns", "expected a whole number from 2 to the cell's n_turns");
      corridor.n_turns = cn.get<std::size_t>();
      corridor.length_m = Reader::number(co, cp, "length_m");
      if (!(corridor.length_m >= 0.0)) Reader::fail(cp + "/length_m", "must not be negative");
      corridor.lateral_sd_m =
          Reader::numbers(Reader::member(co, cp, "lateral_sd_m"), cp + "/lateral_sd_m");
      if (corridor.lateral_sd_m.size() != kCorridorStations)
        Reader::fail(cp + "/lateral_sd_m",
                     "expected " + std::to_string(kCorridorStations) + " values");
      for (std::size_t i = 0; i < corridor.lateral_sd_m.size(); ++i)
        if (corridor.lateral_sd_m[i] < 0.0)
          Reader::fail(cp + "/lateral_sd_m/" + std::to_string(i), "must not be negative");
      c.corridor = std::move(corridor);
    }
    if (cj.contains("timing")) c.timing = timing_from_json(cj["timing"], path + "/timing");
    cells.push_back(std::move(c));
  }
  Ckt table = Ckt::from_cells(std::move(grid), std::move(cells), options);
  table.vehicle_id = std::move(vehicle_id);
  table.vehicle_length_m = vehicle_length;
  table.created_utc = std::move(created);
  table.frame = frame;
  return table;
}

Ckt parse_ckt_json(std::string_view text) {
  return ckt_from_json(parse_ckt_document(text));
}

json parse_ckt_document(std::string_view text) {
  json doc;
  try {
    doc = parse_json_bounded(text);
  } catch (const JsonSyntaxError& e) {
    // A number too large for a double is reported against its field; other syntax errors by line
    // and column: a person opens the file in an editor to find them.
    if (e.number_out_of_range()) throw ParseError(e.pointer(), e.position(), e.reason());
    throw ParseError("json", e.position(),
                     "CKT file is not valid JSON at line " + std::to_string(e.line()) + " column " +
                         std::to_string(e.column()) + ": " + e.reason());
  }
  return doc;
}

std::string ckt_to_csv(const Ckt& table) {
  std::string out = "speed_mps,dheading_deg,vertex_index,x_m,y_m\n";
  char buf[64];
  const auto num = [&](double v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
  };
  for (const CktCell& c : table.cells()) {
    for (std::size_t i = 0; i < c.trajectory.size(); ++i) {
      num(c.speed_mps);
      out += ',';
      num(c.dheading_deg);
      out += ',';
      out += std::to_string(i);
      out += ',';
      num(c.trajectory[i].x_m);
      out += ',';
      num(c.trajectory[i].y_m);
      out += '\n';
    }
  }
  return out;
}

}  // namespace avk::kinematics
