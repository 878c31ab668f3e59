#include "server/station.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/yaw_model.hpp"
#include "mission/mission_config.hpp"
#include "mission/turn_plan.hpp"
#include "server/analysis.hpp"
#include "server/mission_liveness.hpp"
#include "server/mission_plans.hpp"
#include "server/number_text.hpp"
#include "server/stream_publisher.hpp"
#include "store/store.hpp"

namespace avk::server {

namespace kin = avk::kinematics;
using nlohmann::json;

namespace {

// An error a handler reports: becomes problem+json with this status.
struct ApiError : std::runtime_error {
  ApiError(int s, std::string t, const std::string& detail, json x = json::object())
      : std::runtime_error(detail), status(s), title(std::move(t)), extra(std::move(x)) {}
  int status;
  std::string title;
  json extra;
};

ApiError bad_parameter(const std::string& name, const std::string& why) {
  return ApiError(400, "Bad Request", "parameter '" + name + "': " + why, {{"parameter", name}});
}

ApiResponse problem(int status, const std::string& title, const std::string& detail,
                    json extra = json::object()) {
  json j = {{"type", "about:blank"}, {"title", title}, {"status", status}, {"detail", detail}};
  j.update(extra);
  return {status, "application/problem+json", j.dump(), {}};
}

ApiResponse json_response(const json& j, int status = 200) {
  return {status, "application/json", j.dump(), {}};
}

std::optional<double> number_param(const ApiRequest& r, const std::string& name, double min,
                                   double max) {
  const auto it = r.query.find(name);
  if (it == r.query.end()) return std::nullopt;
  const std::string& v = it->second;
  if (v.empty()) throw bad_parameter(name, "empty");
  std::size_t used = 0;
  double d = 0.0;
  try {
    d = std::stod(v, &used);
  } catch (const std::exception&) {
    throw bad_parameter(name, "not a number: '" + v + "'");
  }
  if (used != v.size()) throw bad_parameter(name, "not a number: '" + v + "'");
  if (!std::isfinite(d)) throw bad_parameter(name, "must be finite");
  if (d < min || d > max)
    throw bad_parameter(name, "must be in [" + num(min) + ", " + num(max) + "], got " + v);
  return d;
}

double required_number(const ApiRequest& r, const std::string& name, double min, double max) {
  const auto v = number_param(r, name, min, max);
  if (!v) throw bad_parameter(name, "missing");
  return *v;
}

std::optional<std::int64_t> id_param(const ApiRequest& r, const std::string& name) {
  const auto v = number_param(r, name, 0, 9.0e15);
  if (!v) return std::nullopt;
  if (std::floor(*v) != *v) throw bad_parameter(name, "must be a whole number");
  return static_cast<std::int64_t>(*v);
}

std::int64_t path_id(const std::string& segment, const std::string& what) {
  std::size_t used = 0;
  long long id = 0;
  try {
    id = std::stoll(segment, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != segment.size() || id <= 0)
    throw ApiError(404, "Not Found", "no " + what + " '" + segment + "'");
  return id;
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : path) {
    if (c == '/') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool media_type_is(const std::string& header, const std::string& type) {
  const std::string base = header.substr(0, header.find(';'));
  std::string t;
  for (char c : base)
    if (c != ' ') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t == type;
}

enum class Format { json, csv };
// ?format= wins; otherwise Accept. Anything the resource cannot produce is 406.
Format negotiate(const ApiRequest& r, bool csv_available) {
  if (const auto it = r.query.find("format"); it != r.query.end()) {
    if (it->second == "json") return Format::json;
    if (it->second == "csv" && csv_available) return Format::csv;
    throw bad_parameter("format", csv_available ? "must be json or csv" : "must be json");
  }
  if (r.accept.empty()) return Format::json;
  bool json_ok = false, csv_ok = false;
  std::stringstream s(r.accept);
  std::string item;
  while (std::getline(s, item, ',')) {
    const std::string type = item.substr(0, item.find(';'));
    std::string t;
    for (char c : type)
      if (c != ' ') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (t == "*/*" || t == "application/*" || t == "application/json" ||
        t == "application/problem+json")
      json_ok = true;
    if (t == "text/csv" || t == "text/*") csv_ok = true;
  }
  if (csv_ok && csv_available && !json_ok) return Format::csv;
  if (json_ok) return Format::json;
  if (csv_ok && csv_available) return Format::csv;
  throw ApiError(406, "Not Acceptable",
                 std::string("this resource is available as application/json") +
                     (csv_available ? " and text/csv" : ""));
}

ApiResponse csv_response(std::string body, const std::string& filename = "") {
  ApiResponse r{200, "text/csv; charset=utf-8", std::move(body), {}};
  if (!filename.empty())
    r.headers.push_back({"Content-Disposition", "attachment; filename=\"" + filename + "\""});
  return r;
}

json optional_json(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

json mean_sd_json(const kin::MeanSd& m) {
  return {{"mean", m.mean}, {"sd", m.sd}};
}

json points_json(const kin::Polyline& line) {
  json a = json::array();
  for (const auto& p : line)
    a.push_back({p.x_m, p.y_m});
  return a;
}

json turn_row_json(const store::TurnRow& t) {
  return {{"id", t.id},
          {"mission_id", t.mission_id},
          {"vehicle_id", t.vehicle_id},
          {"status", kin::to_string(t.status)},
          {"reason", t.reason},
          {"speed_mps", t.commanded_speed_mps},
          {"goal_dheading_deg", t.goal_dheading_deg},
          {"observed_dheading_deg", t.observed_dheading_deg},
          {"start_time_s", t.start_time_s},
          {"end_time_s", t.end_time_s},
          {"advance_m", optional_json(t.advance_m)},
          {"transfer_m", optional_json(t.transfer_m)},
          {"condition_set_time_s", optional_json(t.condition_set_time_s)}};
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string optional_csv(const std::optional<double>& v) {
  return v ? num(*v) : std::string();
}

json mission_json(const store::Mission& m) {
  return {{"id", m.id},
          {"vehicle_id", m.vehicle_id},
          {"name", m.name},
          {"status", store::to_string(effective_status(m))},
          {"status_reason", m.status_reason},
          {"created_utc", m.created_utc},
          {"started_s", optional_json(m.started_s)},
          {"ended_s", optional_json(m.ended_s)}};
}

// A value a client sent, for an error message: a scalar shortened, a container by its kind only
// (dumping it whole would grow the message with the input, and recurse as deep as it nests).
std::string describe_value(const json& v) {
  if (v.is_structured()) return std::string("an ") + v.type_name();
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  constexpr std::size_t kMax = 40;
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

// RFC 7235: the scheme is case-insensitive, one or more spaces follow it. The token is compared
// in time independent of where it differs.
bool bearer_token_matches(const std::string& authorization, const std::string& token) {
  constexpr std::string_view scheme = "bearer";
  if (token.empty() || authorization.size() <= scheme.size()) return false;
  for (std::size_t i = 0; i < scheme.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(authorization[i])) != scheme[i]) return false;
  std::size_t start = scheme.size();
  if (authorization[start] != ' ') return false;
  while (start < authorization.size() && authorization[start] == ' ')
    ++start;
  const std::string_view given = std::string_view(authorization).substr(start);
  unsigned char diff = given.size() == token.size() ? 0 : 1;
  for (std::size_t i = 0; i < token.size(); ++i)
    diff |= static_cast<unsigned char>(token[i] ^ (i < given.size() ? given[i] : 0));
  return diff == 0;
}

}  // namespace

struct Station::Impl {
  StationOptions options;
  StreamHub& hub;
  std::unique_ptr<VehicleLoop> loop;

  // One SQLite connection per thread that handles requests.
  store::Store& db() {
    thread_local std::map<std::string, std::unique_ptr<store::Store>> connections;
    auto& c = connections[options.db_path];
    if (!c) c = std::make_unique<store::Store>(options.db_path);
    return *c;
  }

  // The table predictions use, rebuilt when the vehicle's turns change (checked at most every
  // second, so the predict hot path is a lookup).
  struct TableCache {
    std::mutex mutex;
    std::chrono::steady_clock::time_point checked{};
    std::int64_t turns_seen = -1;
    std::int64_t snapshot_seen = -1;
    std::shared_ptr<const kin::Ckt> table;
    std::shared_ptr<const kin::MaterializedCkt> fine;
  };
  std::map<std::string, std::unique_ptr<TableCache>> caches;
  std::mutex caches_mutex;

  Impl(StationOptions o, StreamHub& h) : options(std::move(o)), hub(h) {
    if (options.vehicle)
      loop = std::make_unique<VehicleLoop>(*options.vehicle, options.db_path, hub);
  }

  // --- dispatch --------------------------------------------------------------------------

  ApiResponse handle(const ApiRequest& r) {
    const auto seg = split_path(r.path);
    if (seg.size() < 2 || seg[0] != "api" || seg[1] != "v1")
      throw ApiError(404, "Not Found", "no resource at " + r.path);
    const std::vector<std::string> p(seg.begin() + 2, seg.end());
    authorize(r);
    const bool get = r.method == "GET" || r.method == "HEAD";
    const bool post = r.method == "POST";
    const auto only = [&](bool ok, const char* allow) {
      if (!ok)
        throw ApiError(405, "Method Not Allowed", r.method + " is not allowed on " + r.path,
                       {{"allow", allow}});
    };
    if (p.size() == 1 && p[0] == "health") return only(get, "GET"), health();
    if (p.size() == 1 && p[0] == "vehicles") return only(get, "GET"), vehicles();
    if (p.size() >= 2 && p[0] == "vehicles") {
      const std::string& vid = p[1];
      if (p.size() == 2) return only(get, "GET"), vehicle(vid);
      const std::string& what = p[2];
      if (p.size() == 3 && what == "missions") {
        if (post) return start_mission(r, vid);
        only(get, "GET, POST");
        return list_missions(r, vid);
      }
      if (what == "ckt") {
        if (p.size() == 3) return only(get, "GET"), ckt(r, vid);
        if (p.size() == 4 && p[3] == "cells") return only(get, "GET"), ckt_cell(r, vid);
        if (p.size() == 4 && p[3] == "export") return only(get, "GET"), ckt_export(r, vid);
        if (p.size() == 4 && p[3] == "import") return only(post, "POST"), ckt_import(r, vid);
      }
      if (p.size() == 3 && what == "predict") return only(get, "GET"), predict(r, vid);
      if (p.size() == 3 && what == "compare") return only(get, "GET"), compare(r, vid);
      if (what == "models") {
        if (p.size() == 3) {
          if (post) return fit_model(r, vid);
          only(get, "GET, POST");
          return list_models(vid);
        }
        if (p.size() == 4 && p[3] == "sweep") return only(get, "GET"), sweep(r, vid);
      }
    }
    if (p.size() == 1 && p[0] == "missions") return only(get, "GET"), list_missions(r, "");
    if (p.size() >= 2 && p[0] == "missions") {
      const std::int64_t id = path_id(p[1], "mission");
      if (p.size() == 2) return only(get, "GET"), mission(id);
      if (p.size() == 3 && p[2] == "events") return only(get, "GET"), events(r, id);
      if (p.size() == 3 && p[2] == "nav") return only(get, "GET"), nav(r, id);
      if (p.size() == 3 && (p[2] == "pause" || p[2] == "resume" || p[2] == "abort"))
        return only(post, "POST"), control(id, p[2]);
    }
    if (p.size() == 1 && p[0] == "turns") return only(get, "GET"), turns(r);
    if (p.size() == 2 && p[0] == "turns") return only(get, "GET"), turn(path_id(p[1], "turn"));
    if (p.size() == 2 && p[0] == "models") return only(get, "GET"), model(path_id(p[1], "model"));
    if (p.size() == 3 && p[0] == "models" && p[2] == "headings")
      return only(get, "GET"), headings(r, path_id(p[1], "model"));
    throw ApiError(404, "Not Found", "no resource at " + r.path);
  }

  void authorize(const ApiRequest& r) const {
    // Anything that commands the boat needs the token; so does anything from off this machine.
    const bool needs = r.method != "GET" && r.method != "HEAD";
    if (!needs && r.remote_is_loopback) return;
    if (bearer_token_matches(r.authorization, options.token)) return;
    ApiError e(401, "Unauthorized",
               r.authorization.empty() ? "this endpoint needs the station's bearer token"
                                       : "the bearer token is not the station's");
    throw e;
  }

  // The CKT of a long campaign is bigger than any control request.
  static std::optional<std::size_t> body_limit_of(const ApiRequest& r) {
    const auto seg = split_path(r.path);
    if (seg.size() == 6 && seg[2] == "vehicles" && seg[4] == "ckt" && seg[5] == "import")
      return std::size_t{64} << 20;
    return std::nullopt;
  }

  // --- vehicles --------------------------------------------------------------------------

  ApiResponse health() {
    return json_response({{"status", "ok"},
                          {"server_version", options.server_version},
                          {"session_id", hub.session_id()},
                          {"vehicle_id", loop ? json(loop->info().id) : json()}});
  }

  json vehicle_json(const VehicleSnapshot& s) {
    json j = {{"id", s.info.id},
              {"kind", s.info.kind},
              {"max_speed_mps", s.info.max_speed_mps},
              {"link", vehicle::to_string(s.link)},
              {"helm_mode", s.helm_mode},
              {"desired_heading_deg", optional_json(s.desired_heading_deg)},
              {"desired_speed_mps", optional_json(s.desired_speed_mps)},
              {"mission_id", s.mission_id ? json(*s.mission_id) : json()},
              {"t_s", s.t_s}};
    j["nav"] = s.nav ? json{{"t_s", s.nav->t_s},
                            {"x_m", s.nav->x_m},
                            {"y_m", s.nav->y_m},
                            {"heading_deg", s.nav->heading_deg},
                            {"speed_mps", s.nav->speed_mps}}
                     : json();
    // A real vehicle's link health: what an operator checks before trusting the turns.
    if (s.m200) j["frontseat"] = frontseat_json(*s.m200);
    return j;
  }

  ApiResponse vehicles() {
    json out = json::array();
    if (loop) out.push_back(vehicle_json(loop->snapshot()));
    for (const auto& m : db().list_missions()) {
      const bool listed = std::any_of(out.begin(), out.end(),
                                      [&](const json& v) { return v["id"] == m.vehicle_id; });
      if (!listed) {
        const auto v = db().get_vehicle(m.vehicle_id);
        out.push_back(
            {{"id", m.vehicle_id}, {"kind", v ? json(v->kind) : json()}, {"link", "DISCONNECTED"}});
      }
    }
    return json_response(out);
  }

  VehicleLoop& connected(const std::string& vid) {
    if (!loop || loop->info().id != vid)
      throw ApiError(409, "Conflict", "vehicle '" + vid + "' is not connected to this station");
    return *loop;
  }

  ApiResponse vehicle(const std::string& vid) {
    if (loop && loop->info().id == vid) return json_response(vehicle_json(loop->snapshot()));
    if (db().get_vehicle(vid))
      return json_response({{"id", vid}, {"link", "DISCONNECTED"}, {"nav", nullptr}});
    throw ApiError(404, "Not Found", "no vehicle '" + vid + "'");
  }

  // --- missions --------------------------------------------------------------------------

  ApiResponse start_mission(const ApiRequest& r, const std::string& vid) {
    if (!media_type_is(r.content_type, "application/json"))
      throw ApiError(415, "Unsupported Media Type",
                     "a mission is a JSON document (application/json)");
    VehicleLoop& l = connected(vid);
    if (const auto busy = l.attached_mission())
      throw ApiError(409, "Conflict", "mission " + std::to_string(*busy) + " is running",
                     {{"mission_id", *busy}});
    MissionPlan plan;
    try {
      plan = create_mission_plan(db(), r.body, l.info());
    } catch (const mission::MissionConfigError& e) {
      json errors = json::array();
      for (const auto& f : e.errors())
        errors.push_back({{"field", f.field}, {"message", f.message}});
      throw ApiError(422, "Unprocessable Content", "the mission is not valid",
                     {{"errors", errors}});
    }
    const std::int64_t id = plan.mission_id;
    if (!l.attach(std::move(plan))) {
      db().set_mission_status(id, store::MissionStatus::aborted, "another mission started first",
                              0.0);
      throw ApiError(409, "Conflict", "another mission is running");
    }
    ApiResponse resp =
        json_response({{"id", id}, {"location", "/api/v1/missions/" + std::to_string(id)}}, 201);
    resp.headers.push_back({"Location", "/api/v1/missions/" + std::to_string(id)});
    return resp;
  }

  ApiResponse list_missions(const ApiRequest& r, const std::string& vid) {
    const Format f = negotiate(r, true);
    std::vector<store::Mission> ms;
    for (auto& m : db().list_missions())
      if (vid.empty() || m.vehicle_id == vid) ms.push_back(std::move(m));
    if (f == Format::csv) {
      std::string csv = "id,vehicle_id,name,status,created_utc,started_s,ended_s\n";
      for (const auto& m : ms)
        csv += std::to_string(m.id) + ',' + csv_cell(m.vehicle_id) + ',' + csv_cell(m.name) + ',' +
               store::to_string(effective_status(m)) + ',' + m.created_utc + ',' +
               optional_csv(m.started_s) + ',' + optional_csv(m.ended_s) + '\n';
      return csv_response(csv);
    }
    json out = json::array();
    for (const auto& m : ms)
      out.push_back(mission_json(m));
    return json_response(out);
  }

  ApiResponse mission(std::int64_t id) {
    const auto m = db().get_mission(id);
    if (!m) throw ApiError(404, "Not Found", "no mission " + std::to_string(id));
    json j = mission_json(*m);
    j["config"] = json::parse(m->config_json, nullptr, false);
    const auto live = loop ? loop->live(id) : std::nullopt;
    if (live && loop->attached_mission() == id) {
      j["live"] = true;
      // Status and helm mode from the same live snapshot: the store's status may be a step
      // ahead of or behind what this response shows of the helm.
      j["status"] = live->state;
      j["helm_mode"] = live->helm_mode;
      j["cells"] = json::parse(cells_json(live->cells));
    } else {
      j["live"] = false;
      // Every planned cell, pending ones too, with what the store holds of it.
      std::vector<mission::CellProgress> planned;
      try {
        const auto config = mission::parse_mission_config(m->config_json, 1e9);
        for (const auto& t : mission::plan_turns(config)) {
          auto it = std::find_if(planned.begin(), planned.end(), [&](const auto& c) {
            return mission::same_cell(c.speed_mps, c.dheading_deg, t.speed_mps, t.dheading_deg);
          });
          if (it == planned.end())
            it = planned.insert(planned.end(), {t.speed_mps, t.dheading_deg});
          ++it->planned;
        }
      } catch (const std::exception&) {
        // An imported log has no turn array: only what was stored.
      }
      const auto stats = db().mission_cell_stats(id);
      json cells = json::array();
      const auto stat_of = [&](double u, double d) -> const store::CellStats* {
        for (const auto& c : stats)
          if (mission::same_cell(c.speed_mps, c.dheading_deg, u, d)) return &c;
        return nullptr;
      };
      const auto cell_json = [&](double u, double d, int plan, const store::CellStats* c) {
        return json{{"speed_mps", u},
                    {"dheading_deg", d},
                    {"planned", plan},
                    {"ok", c ? c->n_ok : 0},
                    {"aborted", c ? c->n_aborted : 0},
                    {"rejected", c ? c->n_rejected : 0},
                    {"advance_m", c && c->advance_m ? mean_sd_json(*c->advance_m) : json()},
                    {"transfer_m", c && c->transfer_m ? mean_sd_json(*c->transfer_m) : json()}};
      };
      for (const auto& p : planned)
        cells.push_back(cell_json(p.speed_mps, p.dheading_deg, p.planned,
                                  stat_of(p.speed_mps, p.dheading_deg)));
      for (const auto& c : stats) {
        const bool listed = std::any_of(planned.begin(), planned.end(), [&](const auto& p) {
          return mission::same_cell(c.speed_mps, c.dheading_deg, p.speed_mps, p.dheading_deg);
        });
        if (!listed) cells.push_back(cell_json(c.speed_mps, c.dheading_deg, 0, &c));
      }
      j["cells"] = std::move(cells);
    }
    std::vector<double> set;
    for (const auto& cs : db().condition_sets(id))
      if (cs.outcome == "set") set.push_back(cs.duration_s());
    j["condition_set_time_s"] = set.empty() ? json() : mean_sd_json(kin::mean_sd(set));
    return json_response(j);
  }

  ApiResponse events(const ApiRequest& r, std::int64_t id) {
    if (!db().get_mission(id)) throw ApiError(404, "Not Found", "no mission " + std::to_string(id));
    const auto after = id_param(r, "after").value_or(0);
    const auto limit = static_cast<int>(number_param(r, "limit", 1, 1000).value_or(100));
    json items = json::array();
    std::int64_t last = after;
    const auto evs = db().list_events(id, after, limit);
    for (const auto& e : evs) {
      items.push_back({{"id", e.id}, {"t_s", e.t_s}, {"kind", e.kind}, {"message", e.message}});
      last = e.id;
    }
    return json_response(
        {{"items", items}, {"next", static_cast<int>(evs.size()) == limit ? json(last) : json()}});
  }

  // The mission's stored track, oldest first. The cursor is the last rowid of a full page: rows
  // recorded while a client pages are appended after it, so nothing is skipped or repeated.
  ApiResponse nav(const ApiRequest& r, std::int64_t id) {
    if (!db().get_mission(id)) throw ApiError(404, "Not Found", "no mission " + std::to_string(id));
    const auto after = id_param(r, "after").value_or(0);
    const double limit_d = number_param(r, "limit", 1, 10000).value_or(5000);
    if (std::floor(limit_d) != limit_d) throw bad_parameter("limit", "must be a whole number");
    const int limit = static_cast<int>(limit_d);
    const auto rows = db().nav_page(id, after, limit);
    json items = json::array();
    for (const auto& [rowid, n] : rows)
      items.push_back({{"t_s", n.t_s},
                       {"x_m", n.x_m},
                       {"y_m", n.y_m},
                       {"heading_deg", n.heading_deg},
                       {"speed_mps", n.speed_mps},
                       {"desired_heading_deg", optional_json(n.desired_heading_deg)},
                       {"desired_speed_mps", optional_json(n.desired_speed_mps)},
                       {"helm_mode", n.helm_mode}});
    const bool full = static_cast<int>(rows.size()) == limit;
    return json_response({{"items", items}, {"next", full ? json(rows.back().rowid) : json()}});
  }

  ApiResponse control(std::int64_t id, const std::string& action) {
    const auto m = db().get_mission(id);
    if (!m) throw ApiError(404, "Not Found", "no mission " + std::to_string(id));
    if (loop && loop->attached_mission() == id) {
      const auto c = action == "pause"    ? VehicleLoop::Command::pause
                     : action == "resume" ? VehicleLoop::Command::resume
                                          : VehicleLoop::Command::abort;
      loop->command(id, c);
      loop->wait_for_tick(std::chrono::milliseconds(2000));
      return mission(id);
    }
    if (action != "resume")
      throw ApiError(409, "Conflict",
                     "mission " + std::to_string(id) + " is not running (" +
                         store::to_string(effective_status(*m)) + ")");
    VehicleLoop& l = connected(m->vehicle_id);
    if (const auto busy = l.attached_mission())
      throw ApiError(409, "Conflict", "mission " + std::to_string(*busy) + " is running");
    MissionPlan plan;
    try {
      plan = resume_mission_plan(db(), id, l.info().max_speed_mps);
    } catch (const std::exception& e) {
      throw ApiError(409, "Conflict", e.what());
    }
    if (!l.attach(std::move(plan))) throw ApiError(409, "Conflict", "another mission is running");
    l.wait_for_tick(std::chrono::milliseconds(2000));
    return mission(id);
  }

  // --- turns -----------------------------------------------------------------------------

  ApiResponse turns(const ApiRequest& r) {
    const Format f = negotiate(r, true);
    store::TurnFilter filter;
    filter.mission_id = id_param(r, "mission");
    filter.speed_mps = number_param(r, "speed", 0.0, 100.0);
    filter.dheading_deg = number_param(r, "dheading", -180.0, 180.0);
    if (const auto it = r.query.find("status"); it != r.query.end()) {
      const auto s = kin::turn_status_from_string(it->second);
      if (!s) throw bad_parameter("status", "must be ok, aborted or rejected");
      filter.status = *s;
    }
    filter.after_id = id_param(r, "after").value_or(0);
    filter.limit = static_cast<int>(number_param(r, "limit", 1, 1000).value_or(100));
    const auto rows = db().list_turns(filter);
    // Keyset pagination: the cursor is the last id of a full page; 0 when there is no more.
    const std::int64_t next =
        static_cast<int>(rows.size()) == filter.limit && !rows.empty() ? rows.back().id : 0;
    if (f == Format::csv) {
      std::string csv =
          "id,mission_id,vehicle_id,status,reason,speed_mps,goal_dheading_deg,"
          "observed_dheading_deg,start_time_s,end_time_s,advance_m,transfer_m,"
          "condition_set_time_s\n";
      for (const auto& t : rows)
        csv += std::to_string(t.id) + ',' + std::to_string(t.mission_id) + ',' +
               csv_cell(t.vehicle_id) + ',' + kin::to_string(t.status) + ',' + csv_cell(t.reason) +
               ',' + num(t.commanded_speed_mps) + ',' + num(t.goal_dheading_deg) + ',' +
               num(t.observed_dheading_deg) + ',' + num(t.start_time_s) + ',' + num(t.end_time_s) +
               ',' + optional_csv(t.advance_m) + ',' + optional_csv(t.transfer_m) + ',' +
               optional_csv(t.condition_set_time_s) + '\n';
      ApiResponse resp = csv_response(csv);
      if (next) resp.headers.push_back({"X-Next-After", std::to_string(next)});
      return resp;
    }
    json items = json::array();
    for (const auto& t : rows)
      items.push_back(turn_row_json(t));
    return json_response({{"items", items}, {"next", next ? json(next) : json()}});
  }

  ApiResponse turn(std::int64_t id) {
    const auto t = db().get_turn(id);
    if (!t) throw ApiError(404, "Not Found", "no turn " + std::to_string(id));
    json j = turn_row_json(t->row);
    j["raw"] = json::parse(kin::to_json_string(t->raw));
    j["normalized"] = t->normalized ? json::parse(kin::to_json_string(*t->normalized)) : json();
    return json_response(j);
  }

  // --- the CKT ---------------------------------------------------------------------------

  TableCache& cache_for(const std::string& vid) {
    std::lock_guard lock(caches_mutex);
    auto& c = caches[vid];
    if (!c) c = std::make_unique<TableCache>();
    return *c;
  }

  // The vehicle's table: built from its stored ok turns, or its latest imported snapshot when it
  // has no turns. 404 when there is neither.
  std::pair<std::shared_ptr<const kin::Ckt>, std::shared_ptr<const kin::MaterializedCkt>> table(
      const std::string& vid) {
    TableCache& c = cache_for(vid);
    std::lock_guard lock(c.mutex);
    const auto now = std::chrono::steady_clock::now();
    if (c.table && now - c.checked < std::chrono::seconds(1)) return {c.table, c.fine};
    c.checked = now;
    const std::int64_t newest = db().newest_ok_turn_id(vid);
    const auto snap = db().latest_ckt_snapshot();
    const std::int64_t snap_id = snap && snap->table.vehicle_id == vid ? snap->id : 0;
    if (c.table && newest == c.turns_seen && snap_id == c.snapshot_seen) return {c.table, c.fine};
    std::shared_ptr<kin::Ckt> t;
    if (newest > 0) {
      t = std::make_shared<kin::Ckt>(kin::Ckt::build(db().load_normalized_turns({}, vid)));
      t->vehicle_id = vid;
    } else if (snap_id > 0) {
      t = std::make_shared<kin::Ckt>(snap->table);
    } else {
      throw ApiError(404, "Not Found", "vehicle '" + vid + "' has no turns and no imported CKT");
    }
    c.turns_seen = newest;
    c.snapshot_seen = snap_id;
    c.table = t;
    c.fine = t->speed_range_mps() ? std::make_shared<kin::MaterializedCkt>(*t) : nullptr;
    return {c.table, c.fine};
  }

  ApiResponse ckt(const ApiRequest& r, const std::string& vid) {
    const Format f = negotiate(r, true);
    const auto t = table(vid).first;
    if (f == Format::csv) return csv_response(kin::ckt_to_csv(*t));
    json cells = json::array();
    for (const auto& c : t->cells()) {
      cells.push_back({{"speed_mps", c.speed_mps},
                       {"dheading_deg", c.dheading_deg},
                       {"n_turns", c.n_turns},
                       {"advance_m", mean_sd_json(c.advance_m)},
                       {"transfer_m", mean_sd_json(c.transfer_m)},
                       {"avk_error_m2", optional_json(c.avk_error_m2)}});
    }
    const auto range = t->speed_range_mps();
    return json_response({{"vehicle_id", vid},
                          {"speeds_mps", t->grid().speeds_mps},
                          {"dheadings_deg", t->grid().dheadings_deg},
                          {"speed_range_mps", range ? json{range->first, range->second} : json()},
                          {"cells", cells}});
  }

  ApiResponse ckt_cell(const ApiRequest& r, const std::string& vid) {
    const double speed = required_number(r, "speed", 0.0, 100.0);
    const double dheading = required_number(r, "dheading", 0.0, 180.0);
    const auto t = table(vid).first;
    const auto si = t->speed_index(speed);
    const auto di = t->dheading_index(dheading);
    if (!si || !di)
      throw ApiError(404, "Not Found",
                     "no cell at " + num(speed) + " m/s, " + num(dheading) + " deg in the table");
    const kin::CktCell& c = t->cell(*si, *di);
    json turns = json::array();
    for (const auto& tr : c.turns)
      turns.push_back({{"mission_id", tr.meta().mission_id},
                       {"initial_heading_deg", tr.meta().initial_heading_deg},
                       {"points", points_json(tr.points())}});
    json j = {{"speed_mps", c.speed_mps},
              {"dheading_deg", c.dheading_deg},
              {"n_turns", c.n_turns},
              {"advance_m", mean_sd_json(c.advance_m)},
              {"transfer_m", mean_sd_json(c.transfer_m)},
              {"avk_error_m2", optional_json(c.avk_error_m2)},
              {"turns", turns},
              {"mean", points_json(c.mean_turn)},
              {"trajectory", points_json(c.trajectory)}};
    j["fit"] = c.fit.domain_max > c.fit.domain_min ? points_json(c.fit.sample(0.1)) : json();
    return json_response(j);
  }

  ApiResponse ckt_export(const ApiRequest& r, const std::string& vid) {
    const auto it = r.query.find("format");
    const std::string format = it == r.query.end() ? "json" : it->second;
    if (format != "json" && format != "csv") throw bad_parameter("format", "must be json or csv");
    kin::Ckt t = *table(vid).first;
    t.vehicle_id = vid;
    if (format == "csv") return csv_response(kin::ckt_to_csv(t), "ckt-" + vid + ".csv");
    ApiResponse resp{200, "application/json", kin::ckt_to_json_string(t), {}};
    resp.headers.push_back(
        {"Content-Disposition", "attachment; filename=\"ckt-" + vid + ".json\""});
    return resp;
  }

  ApiResponse ckt_import(const ApiRequest& r, const std::string& vid) {
    if (!media_type_is(r.content_type, "application/json"))
      throw ApiError(415, "Unsupported Media Type", "a CKT file is JSON (application/json)");
    kin::Ckt t;
    try {
      t = kin::parse_ckt_json(r.body);
    } catch (const std::exception& e) {
      throw ApiError(422, "Unprocessable Content", std::string("not a CKT file: ") + e.what());
    }
    if (t.vehicle_id != vid)
      throw ApiError(422, "Unprocessable Content",
                     "the file's table is for vehicle '" + t.vehicle_id + "', not '" + vid + "'");
    const auto id = db().save_ckt_snapshot(t, {});
    {
      TableCache& c = cache_for(vid);
      std::lock_guard lock(c.mutex);
      c.table.reset();
    }
    return json_response({{"snapshot_id", id}, {"vehicle_id", vid}}, 201);
  }

  // --- predictions, models, comparison ----------------------------------------------------

  ApiResponse predict(const ApiRequest& r, const std::string& vid) {
    const double speed = required_number(r, "speed", 0.0, 100.0);
    const double dheading = required_number(r, "dheading", -180.0, 180.0);
    if (speed <= 0.0) throw bad_parameter("speed", "must be positive");
    if (dheading == 0.0) throw bad_parameter("dheading", "must not be 0");
    const auto x = number_param(r, "x", -1e7, 1e7);
    const auto y = number_param(r, "y", -1e7, 1e7);
    const auto heading = number_param(r, "heading", -360.0, 720.0);
    if ((x || y || heading) && !(x && y && heading))
      throw bad_parameter(x ? (y ? "heading" : "y") : "x", "a pose needs x, y and heading");
    const auto m_it = r.query.find("method");
    const std::string method = m_it == r.query.end() ? "avk" : m_it->second;
    kin::Polyline line;
    json j = {{"method", method},
              {"vehicle_id", vid},
              {"speed_mps", speed},
              {"dheading_deg", dheading},
              {"frame", x ? "world" : "normalized"}};
    if (method == "avk") {
      const auto [t, fine] = table(vid);
      try {
        if (fine) {
          const auto hit = fine->lookup(speed, dheading);
          line = hit.right_turn->trajectory;
          if (hit.side == kin::TurnSide::left)
            for (auto& p : line)
              p.x_m = -p.x_m;
          j["advance_m"] = hit.right_turn->advance_m;
          j["transfer_m"] = hit.right_turn->transfer_m;
        } else {
          const auto p = t->query(speed, dheading);
          line = p.trajectory;
          j["advance_m"] = p.advance_m;
          j["transfer_m"] = p.transfer_m;
        }
      } catch (const kin::CktRangeError& e) {
        throw bad_parameter("speed", e.what());
      }
    } else if (method == "model") {
      const auto id = id_param(r, "model");
      const auto m = id ? db().get_model(*id) : db().latest_model(vid);
      if (!m)
        throw ApiError(
            404, "Not Found",
            id ? "no model " + std::to_string(*id) : "no model of '" + vid + "' is stored");
      line = model_turn(m->model, speed, dheading);
      j["model_id"] = m->id;
    } else if (method == "instantaneous") {
      line = instantaneous_turn_ray(speed, dheading);
    } else {
      throw bad_parameter("method", "must be avk, model or instantaneous");
    }
    if (x) line = kin::place_normalized(line, {*x, *y, *heading}, kin::TurnSide::right);
    j["trajectory"] = points_json(line);
    return json_response(j);
  }

  ApiResponse compare(const ApiRequest& r, const std::string& vid) {
    const Format f = negotiate(r, true);
    const auto id = id_param(r, "model");
    std::optional<store::StoredModel> m = id ? db().get_model(*id) : db().latest_model(vid);
    if (id && !m) throw ApiError(404, "Not Found", "no model " + std::to_string(*id));
    Comparison c;
    try {
      c = compare_from_store(db(), vid, {}, m);
    } catch (const std::runtime_error& e) {
      throw ApiError(404, "Not Found", e.what());
    }
    if (f == Format::csv) return csv_response(comparison_csv(c), "compare-" + vid + ".csv");
    return json_response(comparison_json(c));
  }

  ApiResponse list_models(const std::string& vid) {
    json out = json::array();
    for (const auto& m : db().list_models(vid)) {
      json j = model_json(m);
      j.erase("error_coeffs");
      j.erase("heading_coeffs");
      out.push_back(std::move(j));
    }
    return json_response(out);
  }

  ApiResponse model(std::int64_t id) {
    const auto m = db().get_model(id);
    if (!m) throw ApiError(404, "Not Found", "no model " + std::to_string(id));
    return json_response(model_json(*m));
  }

  ApiResponse headings(const ApiRequest& r, std::int64_t model_id) {
    const auto mission = id_param(r, "mission");
    if (!mission) throw bad_parameter("mission", "missing");
    const double limit = number_param(r, "limit", 1, 100000).value_or(2400);
    if (std::floor(limit) != limit) throw bad_parameter("limit", "must be a whole number");
    const auto m = db().get_model(model_id);
    if (!m) throw ApiError(404, "Not Found", "no model " + std::to_string(model_id));
    if (!db().get_mission(*mission))
      throw ApiError(404, "Not Found", "no mission " + std::to_string(*mission));
    ModelHeadings h;
    try {
      h = model_headings(db(), m->model, *mission, static_cast<std::size_t>(limit));
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const store::StoreError*>(&e)) throw;
      throw ApiError(422, "Unprocessable Content", e.what());
    }
    json j = model_headings_json(h);
    j["model_id"] = model_id;
    j["mission_id"] = *mission;
    return json_response(j);
  }

  kin::IdentificationOptions identification(const json& body) {
    kin::IdentificationOptions o;
    if (body.contains("form")) {
      const auto form = body["form"].is_string()
                            ? kin::yaw_model_form_from_string(body["form"].get<std::string>())
                            : std::nullopt;
      if (!form) throw ApiError(422, "Unprocessable Content", "/form must be thesis or invariant");
      o.form = *form;
    }
    if (body.contains("history_s")) {
      if (!body["history_s"].is_number() || !(body["history_s"].get<double>() > 0.0) ||
          body["history_s"].get<double>() > 120.0)
        throw ApiError(422, "Unprocessable Content", "/history_s must be in (0, 120] seconds");
      o.history_s = body["history_s"].get<double>();
    }
    if (body.contains("refine")) {
      if (!body["refine"].is_boolean())
        throw ApiError(422, "Unprocessable Content", "/refine must be true or false");
      o.refine = body["refine"].get<bool>();
    }
    return o;
  }

  std::vector<std::int64_t> missions_of(const json& v, const std::string& vid) {
    if (!v.is_array() || v.empty())
      throw ApiError(422, "Unprocessable Content", "/missions must be a non-empty array of ids");
    std::vector<std::int64_t> ids;
    for (const auto& e : v) {
      if (!e.is_number_integer() || e.get<std::int64_t>() <= 0)
        throw ApiError(422, "Unprocessable Content",
                       "/missions holds a bad id: " + describe_value(e));
      const auto m = db().get_mission(e.get<std::int64_t>());
      if (!m) throw ApiError(422, "Unprocessable Content", "no mission " + e.dump());
      if (m->vehicle_id != vid)
        throw ApiError(422, "Unprocessable Content",
                       "mission " + e.dump() + " is of vehicle '" + m->vehicle_id + "'");
      ids.push_back(e.get<std::int64_t>());
    }
    return ids;
  }

  ApiResponse fit_model(const ApiRequest& r, const std::string& vid) {
    if (!media_type_is(r.content_type, "application/json"))
      throw ApiError(415, "Unsupported Media Type", "send the fit request as application/json");
    const json body = json::parse(r.body, nullptr, false);
    if (body.is_discarded() || !body.is_object())
      throw ApiError(400, "Bad Request", "the body is not a JSON object");
    const auto missions = missions_of(body.value("missions", json()), vid);
    FittedModel f;
    try {
      f = fit_and_store_model(db(), vid, missions, identification(body));
    } catch (const std::invalid_argument& e) {
      throw ApiError(422, "Unprocessable Content", e.what());
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const store::StoreError*>(&e)) throw;
      throw ApiError(422, "Unprocessable Content", e.what());
    }
    ApiResponse resp = json_response(model_json(f.stored), 201);
    resp.headers.push_back({"Location", "/api/v1/models/" + std::to_string(f.stored.id)});
    return resp;
  }

  ApiResponse sweep(const ApiRequest& r, const std::string& vid) {
    std::vector<std::int64_t> ids;
    for (auto [it, end] = r.multi_query.equal_range("mission"); it != end; ++it) {
      json v = json::parse(it->second, nullptr, false);
      if (!v.is_number_integer()) throw bad_parameter("mission", "must be a mission id");
      ids.push_back(v.get<std::int64_t>());
    }
    if (ids.empty()) throw bad_parameter("mission", "missing");
    json arr = json::array();
    for (auto id : ids)
      arr.push_back(id);
    std::vector<kin::HistorySweepRow> rows;
    try {
      rows = kin::sweep_history(identification_data(db(), missions_of(arr, vid), {}), {},
                                {2, 4, 6, 8, 10, 12, 14, 16, 18, 20});
    } catch (const std::invalid_argument& e) {
      throw ApiError(422, "Unprocessable Content", e.what());
    }
    json out = json::array();
    for (const auto& row : rows)
      out.push_back({{"history_s", row.history_s},
                     {"history_samples", row.history},
                     {"train_one_step_rms_deg", row.train_one_step_rms_deg},
                     {"validation_mse_m2", row.validation.position_mse_m2},
                     {"validation_heading_rms_deg", row.validation.heading_rms_deg},
                     {"validation_turns", row.validation.windows}});
    return json_response(out);
  }
};

Station::Station(StationOptions options, StreamHub& hub)
    : impl_(std::make_unique<Impl>(std::move(options), hub)) {}

Station::~Station() {
  shutdown();
}

void Station::start() {
  store::Store& db = impl_->db();
  mark_orphaned_missions_interrupted(db, 0.0);
  if (impl_->loop) impl_->loop->start();
}

void Station::shutdown() {
  if (impl_->loop) impl_->loop->stop("the server stopped");
}

VehicleLoop* Station::vehicle_loop() {
  return impl_->loop.get();
}

bool Station::may_open_stream(const ApiRequest& request) {
  ApiRequest get = request;
  get.method = "GET";
  try {
    impl_->authorize(get);
    return true;
  } catch (const ApiError&) {
    return false;
  }
}

Admission Station::admit(const ApiRequest& head) {
  Admission a;
  a.body_limit_bytes = Impl::body_limit_of(head);
  try {
    impl_->authorize(head);
  } catch (const ApiError& e) {
    ApiResponse r = problem(e.status, e.title, e.what(), e.extra);
    r.headers.push_back({"WWW-Authenticate", "Bearer"});
    a.refusal = std::move(r);
  }
  return a;
}

ApiResponse Station::handle(const ApiRequest& request) {
  try {
    // A HEAD gets the GET's body; the transport sends its length and drops it.
    return impl_->handle(request);
  } catch (const ApiError& e) {
    ApiResponse r = problem(e.status, e.title, e.what(), e.extra);
    if (e.status == 405 && e.extra.contains("allow"))
      r.headers.push_back({"Allow", e.extra["allow"].get<std::string>()});
    if (e.status == 401) r.headers.push_back({"WWW-Authenticate", "Bearer"});
    return r;
  } catch (const std::exception& e) {
    return problem(500, "Internal Server Error", e.what());
  }
}

}  // namespace avk::server
