// The station's REST handlers over a real store and a real simulated vehicle (paced fast), called
// without sockets: every endpoint and every error path of the REST API.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "kinematics/ckt_file.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/sim_station.hpp"
#include "support/temp_db.hpp"

using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::Station;
using avk::server::StreamHub;
using nlohmann::json;

namespace {

constexpr const char* kToken = "test-token";

// Four turns of the Figure 4-1 kind on a wide region.
std::string small_mission(double speed2 = 1.0) {
  return json{
      {"name", "api-test"},
      {"turn_array", {{"speeds_mps", {0.5, speed2}}, {"dheadings_deg", {40, 100}}, {"repeats", 1}}},
      {"operating_region",
       {{"polygon_m", {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}},
        {"buffer_m", 25},
        {"return_point_m", {0, -70}}}}}
      .dump();
}

ApiRequest get(const std::string& path, std::map<std::string, std::string> query = {}) {
  ApiRequest r;
  r.method = "GET";
  r.path = path;
  for (const auto& [k, v] : query)
    r.multi_query.emplace(k, v);
  r.query = std::move(query);
  return r;
}

ApiRequest post(const std::string& path, const std::string& body = "{}",
                const std::string& token = kToken) {
  ApiRequest r;
  r.method = "POST";
  r.path = path;
  r.body = body;
  r.content_type = "application/json";
  if (!token.empty()) r.authorization = "Bearer " + token;
  return r;
}

json body(const ApiResponse& r) {
  return json::parse(r.body);
}

std::string header(const ApiResponse& r, const std::string& name) {
  for (const auto& [k, v] : r.headers)
    if (k == name) return v;
  return "";
}

// --- docs/api.md, read as a client reads it ----------------------------------------------

std::string api_doc() {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/docs/api.md");
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// A row of a route table: `| GET | `/path?query`, `/other` | what it does |`.
struct DocRow {
  std::string method;
  std::vector<std::string> patterns;  // with /api/v1, without the query
  std::string description;
};

std::vector<DocRow> documented_routes() {
  std::vector<DocRow> rows;
  std::istringstream lines(api_doc());
  // The path cell may hold escaped bars (`format=json\|csv`).
  const std::regex row(R"(^\| *(GET|POST|PUT|PATCH|DELETE) *\| *((?:[^|\\]|\\.)*)\|(.*)$)");
  const std::regex code("`([^`]*)`");
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    DocRow r{m[1], {}, m[3]};
    const std::string cell = m[2];
    for (auto it = std::sregex_iterator(cell.begin(), cell.end(), code);
         it != std::sregex_iterator(); ++it) {
      std::string path = (*it)[1];
      if (path.empty() || path.front() != '/') continue;
      path = path.substr(0, path.find_first_of("?["));
      r.patterns.push_back("/api/v1" + path);
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

// The fenced example whose request line starts with `request`: the lines after it up to the
// closing fence or an empty line.
std::string doc_example_answer(const std::string& request) {
  std::istringstream lines(api_doc());
  std::string line, answer;
  bool in = false;
  while (std::getline(lines, line)) {
    if (!in) {
      in = line.rfind(request, 0) == 0;
      continue;
    }
    if (line.empty() || line.rfind("```", 0) == 0) break;
    answer += line + "\n";
  }
  return answer;
}

// Every "key": of an example's text.
std::set<std::string> example_keys(const std::string& text) {
  std::set<std::string> keys;
  const std::regex key(R"re("([A-Za-z_][A-Za-z0-9_]*)"\s*:)re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), key); it != std::sregex_iterator();
       ++it)
    keys.insert((*it)[1]);
  return keys;
}

void collect_keys(const json& j, std::set<std::string>& keys) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      keys.insert(k);
      collect_keys(v, keys);
    }
  } else if (j.is_array()) {
    for (const auto& v : j)
      collect_keys(v, keys);
  }
}

// The request line of an example as an ApiRequest: "GET /api/v1/...?a=1&b=2".
ApiRequest example_request(const std::string& line) {
  std::istringstream words(line);
  std::string method, target;
  words >> method >> target;
  ApiRequest r;
  r.method = method;
  r.path = target.substr(0, target.find('?'));
  if (const auto q = target.find('?'); q != std::string::npos) {
    std::istringstream pairs(target.substr(q + 1));
    std::string pair;
    while (std::getline(pairs, pair, '&')) {
      const auto eq = pair.find('=');
      r.query[pair.substr(0, eq)] = eq == std::string::npos ? "" : pair.substr(eq + 1);
      r.multi_query.emplace(pair.substr(0, eq), r.query[pair.substr(0, eq)]);
    }
  }
  return r;
}

// The doc's example answer and the real one agree: every key the example shows is in the real
// answer, and every key of the real answer's top level is in the example.
void expect_example_matches(const std::string& request_line, const json& real) {
  const std::string example = doc_example_answer(request_line);
  ASSERT_FALSE(example.empty()) << "docs/api.md has no example '" << request_line << "'";
  std::set<std::string> real_keys;
  collect_keys(real, real_keys);
  for (const auto& k : example_keys(example))
    EXPECT_TRUE(real_keys.count(k)) << "the example of '" << request_line << "' shows \"" << k
                                    << "\", which the real answer lacks: " << real.dump();
  const auto shown = example_keys(example);
  for (const auto& [k, v] : real.items())
    EXPECT_TRUE(shown.count(k)) << "the example of '" << request_line << "' lacks \"" << k
                                << "\" of the real answer";
}

class StationApi : public ::testing::Test {
 protected:
  void SetUp() override { start(); }
  void TearDown() override { station_.reset(); }

  // telemetry_hz: how often the vehicle's snapshot is refreshed besides the helm's own updates.
  void start(double realtime_factor = 400.0, double telemetry_hz = 10.0) {
    station_ = std::make_unique<Station>(
        avk::testing::sim_station_options(db_.path(), kToken, realtime_factor, telemetry_hz), hub_);
    station_->start();
  }

  ApiResponse call(const ApiRequest& r) { return station_->handle(r); }

  // Polls the mission until its status is one of `states` (bounded: 60 s).
  json wait_for(std::int64_t id, const std::set<std::string>& states) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    json m;
    while (std::chrono::steady_clock::now() < deadline) {
      m = body(call(get("/api/v1/missions/" + std::to_string(id))));
      if (states.count(m["status"].get<std::string>())) return m;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "mission " << id << " stayed " << m["status"];
    return m;
  }

  std::int64_t start_mission(const std::string& config = small_mission()) {
    const ApiResponse r = call(post("/api/v1/vehicles/sim-usim/missions", config));
    EXPECT_EQ(r.status, 201) << r.body;
    return body(r)["id"].get<std::int64_t>();
  }

  avk::testing::TempDb db_{"avk_station_api"};
  StreamHub hub_;
  std::unique_ptr<Station> station_;
};

// The station's route table without a vehicle: routes answer before any data exists.
class RouteTable : public ::testing::Test {
 protected:
  RouteTable() {
    avk::server::StationOptions o;
    o.db_path = db_.path();
    o.token = kToken;
    o.server_version = "test";
    station_ = std::make_unique<Station>(o, hub_);
  }
  // A concrete path of a pattern: {vid} the test vehicle, any other {name} 1.
  static std::string concrete(const std::string& pattern) {
    return std::regex_replace(std::regex_replace(pattern, std::regex("\\{vid\\}"), "sim-usim"),
                              std::regex("\\{[a-z_]+\\}"), "1");
  }
  ApiResponse call_station(const ApiRequest& r) { return station_->handle(r); }
  static bool offers_csv(const avk::server::Route& r) {
    for (const auto& rep : r.representations)
      if (rep.media_type == "text/csv") return true;
    return false;
  }
  avk::testing::TempDb db_{"avk_route_table"};
  StreamHub hub_;
  std::unique_ptr<Station> station_;
};

// The API doc and the server must agree: every route the server registers is in a
// route table of docs/api.md, and every route the doc lists is registered (method and pattern).
TEST_F(RouteTable, EveryRouteIsDocumentedAndEveryDocumentedRouteExists) {
  std::set<std::pair<std::string, std::string>> served, documented;
  for (const auto& r : station_->routes())
    served.insert({r.method, r.pattern});
  const auto rows = documented_routes();
  ASSERT_GT(rows.size(), 20u) << "docs/api.md's route tables were not found";
  for (const auto& row : rows) {
    EXPECT_FALSE(row.patterns.empty()) << "a row of docs/api.md names no path: " << row.description;
    for (const auto& p : row.patterns)
      documented.insert({row.method, p});
  }
  for (const auto& [method, pattern] : served)
    EXPECT_TRUE(documented.count({method, pattern}))
        << method << " " << pattern << " is served but not in docs/api.md";
  for (const auto& [method, pattern] : documented)
    EXPECT_TRUE(served.count({method, pattern}))
        << method << " " << pattern << " is in docs/api.md but the server has no such route";
}

// The doc's route tables say "CSV" on exactly the routes that serve it.
TEST_F(RouteTable, TheDocSaysCsvWhereCsvIsServed) {
  std::map<std::pair<std::string, std::string>, bool> says_csv;
  for (const auto& row : documented_routes())
    for (const auto& p : row.patterns)
      says_csv[{row.method, p}] =
          says_csv[{row.method, p}] || row.description.find("CSV") != std::string::npos;
  for (const auto& r : station_->routes()) {
    const bool says = says_csv[std::make_pair(r.method, r.pattern)];
    EXPECT_EQ(says, offers_csv(r)) << r.method << " " << r.pattern
                                   << (offers_csv(r) ? " serves CSV; its row does not say so"
                                                     : " serves no CSV; its row says CSV");
  }
  // The four that once answered JSON to a CSV request.
  for (const std::string p : {"/api/v1/vehicles", "/api/v1/missions/{id}/events",
                              "/api/v1/missions/{id}/nav", "/api/v1/vehicles/{vid}/models"}) {
    bool found = false;
    for (const auto& r : station_->routes())
      if (r.method == "GET" && r.pattern == p) found = offers_csv(r);
    EXPECT_TRUE(found) << p << " offers no CSV";
  }
}

// Content negotiation is the same on every route: an Accept that excludes everything a route
// offers is a 406 naming what it offers, decided before the handler (an unknown id included).
TEST_F(RouteTable, EveryRouteRefusesAnUnacceptableAcceptAlike) {
  for (const auto& route : station_->routes()) {
    ApiRequest r =
        route.method == "GET" ? get(concrete(route.pattern)) : post(concrete(route.pattern), "{}");
    const std::string what = route.method + " " + route.pattern;
    r.accept = "image/png";
    const ApiResponse png = call_station(r);
    EXPECT_EQ(png.status, 406) << what << ": " << png.body;
    if (png.status == 406) {
      json acceptable = json::array();
      for (const auto& rep : route.representations)
        acceptable.push_back(rep.media_type);
      EXPECT_EQ(body(png)["acceptable"], acceptable) << what;
      EXPECT_EQ(png.content_type, "application/problem+json") << what;
    }
    // CSV only: 406 unless the route offers it.
    r.accept = "text/csv";
    const ApiResponse csv = call_station(r);
    EXPECT_EQ(csv.status == 406, !offers_csv(route))
        << what << ": " << csv.status << " " << csv.body;
    // JSON refused by weight: the same as not naming it.
    r.accept = "application/json;q=0, text/csv";
    EXPECT_EQ(call_station(r).status == 406, !offers_csv(route)) << what;
    // Anything: never a 406.
    r.accept = "*/*";
    EXPECT_NE(call_station(r).status, 406) << what;
    if (route.method == "GET" && route.representations.front().format == "json") {
      r.accept.clear();
      r.query["format"] = "xml";
      r.multi_query.emplace("format", "xml");
      const ApiResponse bad = call_station(r);
      EXPECT_EQ(bad.status, 400) << what;
      EXPECT_EQ(body(bad)["parameter"], "format") << what;
    }
  }
}

// An unauthenticated DELETE from afar once got 401. A method the path does not take is a
// 405 with Allow from any address, token or not, before the body is read; a path that is no
// route stays a 401 from afar without the token.
// Which requests the transport answers on an I/O thread, runs on any request worker, or limits
// as expensive (docs/api.md, "Request work"): decided from the header, by the route table.
TEST_F(RouteTable, EachRouteSaysHowMuchWorkItsAnswerTakes) {
  using avk::server::Workload;
  const auto workload = [&](ApiRequest r) { return station_->admit(r).workload; };
  EXPECT_EQ(workload(get("/api/v1/health")), Workload::immediate);
  EXPECT_EQ(workload(get("/api/v1/meta")), Workload::immediate);
  EXPECT_EQ(workload(get("/api/v1/vehicles/sim-usim")), Workload::cheap);
  EXPECT_EQ(workload(get("/api/v1/missions/1")), Workload::cheap);
  EXPECT_EQ(workload(post("/api/v1/missions/1/abort")), Workload::cheap);
  const std::map<std::string, std::string> turn = {{"speed", "1"}, {"dheading", "90"}};
  EXPECT_EQ(workload(get("/api/v1/vehicles/sim-usim/predict", turn)), Workload::cheap);
  for (const char* held_out : {"without_turn", "without_mission", "initial_yaw_rate"}) {
    auto q = turn;
    q[held_out] = "1";
    EXPECT_EQ(workload(get("/api/v1/vehicles/sim-usim/predict", q)), Workload::expensive)
        << held_out;
  }
  for (const auto& r :
       {get("/api/v1/vehicles/sim-usim/compare"), get("/api/v1/vehicles/sim-usim/models/sweep"),
        get("/api/v1/missions/1/export", {{"format", "mcap"}}),
        post("/api/v1/vehicles/sim-usim/maneuvers/evaluate"),
        post("/api/v1/vehicles/sim-usim/models"), post("/api/v1/missions/1/harvest")})
    EXPECT_EQ(workload(r), Workload::expensive) << r.method << " " << r.path;
  // Off this machine without the token: refused from the header, whatever the route's work.
  ApiRequest afar = get("/api/v1/vehicles/sim-usim/compare");
  afar.remote_is_loopback = false;
  EXPECT_TRUE(station_->admit(afar).refusal);
}

TEST_F(RouteTable, AMethodNotAllowedIs405BeforeTheTokenIsAskedFor) {
  for (const bool loopback : {true, false}) {
    ApiRequest del = get("/api/v1/missions/1");
    del.method = "DELETE";
    del.remote_is_loopback = loopback;
    const ApiResponse res = call_station(del);
    EXPECT_EQ(res.status, 405) << "loopback " << loopback << ": " << res.body;
    EXPECT_EQ(header(res, "Allow"), "GET");
    const auto admission = station_->admit(del);
    ASSERT_TRUE(admission.refusal) << "refused from the header, before any body";
    EXPECT_EQ(admission.refusal->status, 405);
    ApiRequest post_health = post("/api/v1/health", "{}", "");
    post_health.remote_is_loopback = loopback;
    EXPECT_EQ(call_station(post_health).status, 405);
  }
  ApiRequest nothing = get("/api/v1/nothing");
  nothing.remote_is_loopback = false;
  EXPECT_EQ(call_station(nothing).status, 401);
  ApiRequest control = post("/api/v1/missions/1/abort", "{}", "");
  control.remote_is_loopback = false;
  EXPECT_EQ(call_station(control).status, 401) << "the right method still needs the token";
}

TEST_F(StationApi, HealthAndVehicle) {
  const json h = body(call(get("/api/v1/health")));
  EXPECT_EQ(h["status"], "ok");
  EXPECT_EQ(h["session_id"], hub_.session_id());
  EXPECT_EQ(h["vehicle_id"], "sim-usim");
  // The station clock beside the wall clock (for the dashboard's wall-clock times).
  const auto now_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  ASSERT_TRUE(h["utc_ms"].is_number_integer()) << h.dump();
  EXPECT_LE(h["utc_ms"].get<std::int64_t>(), now_ms);
  EXPECT_GT(h["utc_ms"].get<std::int64_t>(), now_ms - 600'000);  // taken during this test
  EXPECT_EQ(h["realtime_factor"], 400.0);
  ASSERT_TRUE(h["clock_s"].is_number() && h["session_start_clock_s"].is_number()) << h.dump();
  EXPECT_GE(h["clock_s"].get<double>(), h["session_start_clock_s"].get<double>());
  EXPECT_TRUE(h["datum"].is_null());
  // The simulated vehicle runs from the start: navigation arrives and the link goes live.
  json v;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    v = body(call(get("/api/v1/vehicles/sim-usim")));
    if (v["link"] == "LIVE") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(v["link"], "LIVE");
  EXPECT_TRUE(v["nav"].is_object());
  EXPECT_TRUE(v["helm_mode"].is_null()) << v.dump();  // no mission drives the helm
  EXPECT_EQ(call(get("/api/v1/vehicles/nobody")).status, 404);
  EXPECT_EQ(body(call(get("/api/v1/vehicles"))).size(), 1u);
  // Before any mission the vehicle's motion is the defaults.
  const json motion = body(call(get("/api/v1/vehicles/sim-usim/motion")));
  EXPECT_EQ(motion["speed_reference"]["value"], "over_ground");
  EXPECT_EQ(motion["speed_reference"]["source"], "default");
  EXPECT_TRUE(motion["speed_reference"]["mission_id"].is_null());
  EXPECT_EQ(motion["drift_scatter"]["source"], "default");
  EXPECT_EQ(motion["drift_scatter"]["along_mps"], 0.10);
  EXPECT_TRUE(motion["current"].is_null());
  EXPECT_EQ(call(get("/api/v1/vehicles/nobody/motion")).status, 404);
}

TEST_F(StationApi, ControlNeedsTheTokenAndReadsFromAfarToo) {
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", small_mission(), "")).status, 401);
  const ApiResponse wrong = call(post("/api/v1/vehicles/sim-usim/missions", small_mission(), "x"));
  EXPECT_EQ(wrong.status, 401);
  EXPECT_EQ(wrong.content_type, "application/problem+json");
  ApiRequest remote = get("/api/v1/health");
  remote.remote_is_loopback = false;
  EXPECT_EQ(call(remote).status, 401);
  remote.authorization = std::string("Bearer ") + kToken;
  EXPECT_EQ(call(remote).status, 200);
  // Nothing was created by the refused requests.
  EXPECT_TRUE(body(call(get("/api/v1/missions"))).empty());
}

TEST_F(StationApi, BadRequestsAreProblemsNamingWhatIsWrong) {
  ApiRequest text = post("/api/v1/vehicles/sim-usim/missions", small_mission());
  text.content_type = "text/plain";
  EXPECT_EQ(call(text).status, 415);
  const ApiResponse invalid =
      call(post("/api/v1/vehicles/sim-usim/missions", R"({"name":"x","turn_array":{}})"));
  EXPECT_EQ(invalid.status, 422);
  const json p = body(invalid);
  EXPECT_EQ(p["status"], 422);
  ASSERT_TRUE(p["errors"].is_array());
  bool names_speeds = false;
  for (const auto& e : p["errors"])
    names_speeds |= e["field"] == "/turn_array/speeds_mps";
  EXPECT_TRUE(names_speeds) << p.dump();
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", "{not json")).status, 422);
  EXPECT_EQ(call(post("/api/v1/health")).status, 405);
  EXPECT_EQ(call(get("/api/v1/nothing/here")).status, 404);
  EXPECT_EQ(call(get("/api/v1/missions/abc")).status, 404);
  EXPECT_EQ(call(get("/api/v1/missions/42")).status, 404);
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"limit", "abc"},
                                                        {"limit", "nan"},
                                                        {"limit", "0"},
                                                        {"speed", "1e999"},
                                                        {"after", "-3"},
                                                        {"status", "great"}}) {
    const ApiResponse r = call(get("/api/v1/turns", {{name, value}}));
    EXPECT_EQ(r.status, 400) << name << "=" << value;
    EXPECT_NE(body(r)["detail"].get<std::string>().find(name), std::string::npos) << r.body;
  }
  ApiRequest png = get("/api/v1/turns");
  png.accept = "image/png";
  EXPECT_EQ(call(png).status, 406);
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "1"}})).status, 400);
}

TEST_F(StationApi, MissionRunsPausesResumesAndEveryTurnIsServed) {
  const std::int64_t id = start_mission();
  // Another mission while this one runs: 409.
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", small_mission())).status, 409);
  json m = body(call(get("/api/v1/missions/" + std::to_string(id))));
  EXPECT_EQ(m["cells"].size(), 4u);
  const ApiResponse paused = call(post("/api/v1/missions/" + std::to_string(id) + "/pause"));
  EXPECT_EQ(paused.status, 200) << paused.body;
  EXPECT_EQ(wait_for(id, {"paused"})["status"], "paused");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim")))["helm_mode"], "PAUSED");
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/resume")).status, 200);
  m = wait_for(id, {"done", "halted", "aborted"});
  EXPECT_EQ(m["status"], "done") << m.dump();
  // Every turn the mission finished is in /turns and in the table.
  const json turns =
      body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}, {"status", "ok"}})));
  EXPECT_EQ(turns["items"].size(), 4u) << turns.dump();
  const json ckt = body(call(get("/api/v1/vehicles/sim-usim/ckt")));
  int n = 0;
  for (const auto& c : ckt["cells"])
    n += c["n_turns"].get<int>();
  EXPECT_EQ(n, 4);
  // Control of a finished mission is a conflict.
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/pause")).status, 409);
}

// Pause is one step across mission and helm: whoever reads the mission as paused reads the
// vehicle's helm as PAUSED too. The vehicle's telemetry refreshes only every 20 s of mission
// clock here (a second of wall time), so a helm mode that waited for it would show the mode from
// before the pause; the helm's own update must carry it.
TEST_F(StationApi, APausedMissionIsNeverShownWithAHelmThatIsNotPaused) {
  station_.reset();
  start(20.0, 0.05);
  const std::int64_t id = start_mission();
  const std::string mission_path = "/api/v1/missions/" + std::to_string(id);
  // Wait until the helm has taken the mission up (the vehicle names it).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  json v;
  while (std::chrono::steady_clock::now() < deadline) {
    v = body(call(get("/api/v1/vehicles/sim-usim")));
    if (v["mission_id"] == id) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(v["mission_id"], id) << v.dump();
  const ApiResponse paused = call(post(mission_path + "/pause"));
  ASSERT_EQ(paused.status, 200) << paused.body;
  // The answer may come before the helm tick applied the pause (under load); if it says paused,
  // its helm says so too.
  const json answer = body(paused);
  if (answer["status"] == "paused") {
    EXPECT_EQ(answer["helm_mode"], "PAUSED") << paused.body;
  }
  const json m = wait_for(id, {"paused"});
  EXPECT_EQ(m["helm_mode"], "PAUSED") << m.dump();
  v = body(call(get("/api/v1/vehicles/sim-usim")));
  EXPECT_EQ(v["helm_mode"], "PAUSED") << v.dump();
  EXPECT_EQ(v["mission_id"], id);
  EXPECT_TRUE(v["desired_speed_mps"].is_null()) << v.dump();  // all stop
  // The mission list reads the store, which records the pause after the helm has it.
  const json list = body(call(get("/api/v1/missions")));
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["status"], "paused");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim")))["helm_mode"], "PAUSED");
  EXPECT_EQ(call(post(mission_path + "/abort")).status, 200);
  EXPECT_EQ(wait_for(id, {"aborted"})["status"], "aborted");
}

TEST_F(StationApi, AbortStopsTheVehicle) {
  const std::int64_t id = start_mission();
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/abort")).status, 200);
  EXPECT_EQ(wait_for(id, {"aborted"})["status"], "aborted");
  // The next mission may start.
  const std::int64_t next = start_mission();
  EXPECT_GT(next, id);
}

TEST_F(StationApi, ShutdownInterruptsAndANewStationResumes) {
  const std::int64_t id = start_mission();
  // Let it record at least one turn, then stop the station as SIGTERM would.
  for (int i = 0; i < 3000; ++i) {
    if (!body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}})))["items"].empty())
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  station_->shutdown();
  {
    avk::store::Store s(db_.path());
    EXPECT_EQ(s.missions().get(id)->status, avk::store::MissionStatus::interrupted);
    EXPECT_TRUE(s.integrity_check());
  }
  station_.reset();
  start();
  EXPECT_EQ(body(call(get("/api/v1/missions/" + std::to_string(id))))["status"], "interrupted");
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/resume")).status, 200);
  EXPECT_EQ(wait_for(id, {"done", "halted"})["status"], "done");
  const json ok =
      body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}, {"status", "ok"}})));
  EXPECT_EQ(ok["items"].size(), 4u);
}

TEST_F(StationApi, TurnsPageByKeysetAndComeAsCsv) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const json first = body(call(get("/api/v1/turns", {{"limit", "2"}})));
  ASSERT_EQ(first["items"].size(), 2u);
  ASSERT_TRUE(first["next"].is_number());
  const json second =
      body(call(get("/api/v1/turns", {{"limit", "2"}, {"after", first["next"].dump()}})));
  ASSERT_FALSE(second["items"].empty());
  EXPECT_GT(second["items"][0]["id"].get<int>(), first["items"][1]["id"].get<int>());
  ApiRequest csv = get("/api/v1/turns");
  csv.accept = "text/csv";
  const ApiResponse c = call(csv);
  EXPECT_EQ(c.status, 200);
  EXPECT_EQ(c.content_type.rfind("text/csv", 0), 0u);
  EXPECT_EQ(c.body.rfind("id,mission_id,vehicle_id,status,reason,speed_mps,goal_dheading_deg", 0),
            0u);
  EXPECT_NE(c.body.find("advance_m"), std::string::npos);
  const auto tid = first["items"][0]["id"].get<std::int64_t>();
  const json t = body(call(get("/api/v1/turns/" + std::to_string(tid))));
  // The raw and normalised records of the same turn: same samples count, the normalised one
  // starting at the origin.
  ASSERT_TRUE(t["raw"]["samples"].is_array());
  ASSERT_TRUE(t["normalized"]["samples"].is_array());
  EXPECT_GT(t["raw"]["samples"].size(), 3u);
  EXPECT_EQ(t["raw"]["samples"].size(), t["normalized"]["samples"].size());
  EXPECT_EQ(t["normalized"]["normalized"], true);
  EXPECT_DOUBLE_EQ(t["normalized"]["samples"][0][1].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(t["normalized"]["samples"][0][2].get<double>(), 0.0);
  EXPECT_TRUE(t["normalized"].is_object());
  EXPECT_EQ(call(get("/api/v1/turns/999999")).status, 404);
}

TEST_F(StationApi, CktCellsExportImportPredictModelsCompare) {
  wait_for(start_mission(), {"done"});
  wait_for(start_mission(), {"done"});  // two turns a cell for the comparison
  const json cell = body(
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.5"}, {"dheading", "100"}})));
  EXPECT_EQ(cell["n_turns"], 2);
  EXPECT_EQ(cell["turns"].size(), 2u);
  EXPECT_FALSE(cell["mean"].empty());
  EXPECT_FALSE(cell["trajectory"].empty());
  EXPECT_EQ(
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.7"}, {"dheading", "100"}}))
          .status,
      404);
  // A signed heading change, as predict takes it: the port cell is the cell of |Δψ|
  // mirrored, and says so.
  EXPECT_EQ(cell["side"], "starboard");
  const ApiResponse port_res =
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.5"}, {"dheading", "-100"}}));
  ASSERT_EQ(port_res.status, 200) << port_res.body;
  const json port = body(port_res);
  EXPECT_EQ(port["side"], "port");
  EXPECT_EQ(port["dheading_deg"], -100.0);
  EXPECT_EQ(port["n_turns"], cell["n_turns"]);
  for (const char* line : {"trajectory", "mean", "fit"}) {
    ASSERT_EQ(port[line].size(), cell[line].size()) << line;
    for (std::size_t i = 0; i < cell[line].size(); ++i) {
      EXPECT_EQ(port[line][i][0].get<double>(), -cell[line][i][0].get<double>()) << line;
      EXPECT_EQ(port[line][i][1].get<double>(), cell[line][i][1].get<double>()) << line;
    }
  }
  EXPECT_EQ(port["turns"][0]["points"][3][0].get<double>(),
            -cell["turns"][0]["points"][3][0].get<double>());
  // A starboard right turn ends to the east, the port one to the west.
  EXPECT_GT(cell["trajectory"].back()[0].get<double>(), 0.0);
  EXPECT_LT(port["trajectory"].back()[0].get<double>(), 0.0);
  EXPECT_EQ(
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.5"}, {"dheading", "-181"}}))
          .status,
      400);
  const ApiResponse exported =
      call(get("/api/v1/vehicles/sim-usim/ckt/export", {{"format", "json"}}));
  ASSERT_EQ(exported.status, 200);
  bool disposition = false;
  for (const auto& [k, v] : exported.headers)
    disposition |= k == "Content-Disposition";
  EXPECT_TRUE(disposition);
  EXPECT_NO_THROW(avk::kinematics::parse_ckt_json(exported.body));
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/ckt/import", exported.body)).status, 201);
  EXPECT_EQ(call(post("/api/v1/vehicles/other/ckt/import", exported.body)).status, 422);
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/ckt/import", R"({"schema":99})")).status, 422);
  // Its free text is bounded: the vehicle id (64 bytes) and created_utc (64 bytes).
  const ApiResponse long_id =
      call(post("/api/v1/vehicles/" + std::string(65, 'v') + "/ckt/import", exported.body));
  EXPECT_EQ(long_id.status, 422);
  EXPECT_EQ(body(long_id)["pointer"], "/vehicle_id") << long_id.body;
  EXPECT_NE(long_id.body.find("at most 64 bytes"), std::string::npos) << long_id.body;
  json stamped = json::parse(exported.body);
  stamped["created_utc"] = std::string(100, '9');
  const ApiResponse long_stamp = call(post("/api/v1/vehicles/sim-usim/ckt/import", stamped.dump()));
  EXPECT_EQ(long_stamp.status, 422);
  EXPECT_EQ(body(long_stamp)["pointer"], "/created_utc") << long_stamp.body;

  const json avk = body(call(
      get("/api/v1/vehicles/sim-usim/predict",
          {{"speed", "0.75"}, {"dheading", "-70"}, {"x", "10"}, {"y", "5"}, {"heading", "90"}})));
  EXPECT_EQ(avk["frame"], "world");
  EXPECT_DOUBLE_EQ(avk["trajectory"][0][0].get<double>(), 10.0);
  const ApiResponse too_fast =
      call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "3"}, {"dheading", "70"}}));
  EXPECT_EQ(too_fast.status, 400);  // outside the table's speeds, named with the range
  EXPECT_EQ(body(too_fast)["parameter"], "speed");
  EXPECT_NE(body(too_fast)["detail"].get<std::string>().find("[0.5, 1.0] m/s"), std::string::npos)
      << too_fast.body;
  // Both off, both named, each with its range; the heading change alone, alone.
  const ApiResponse both =
      call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "3"}, {"dheading", "200"}}));
  ASSERT_EQ(both.status, 400) << both.body;
  const json both_p = body(both);
  ASSERT_EQ(both_p["errors"].size(), 2u) << both.body;
  EXPECT_EQ(both_p["errors"][0]["field"], "speed");
  EXPECT_EQ(both_p["errors"][1]["field"], "dheading");
  const std::string detail = both_p["detail"];
  for (const char* part : {"'speed'", "[0.5, 1.0] m/s", "'dheading'", "180"})
    EXPECT_NE(detail.find(part), std::string::npos) << part << " in " << detail;
  const ApiResponse turn_only =
      call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "1"}, {"dheading", "-200"}}));
  EXPECT_EQ(turn_only.status, 400);
  EXPECT_EQ(body(turn_only)["parameter"], "dheading") << turn_only.body;
  EXPECT_FALSE(body(turn_only).contains("errors")) << turn_only.body;
  const ApiResponse missing_both = call(get("/api/v1/vehicles/sim-usim/predict"));
  EXPECT_EQ(body(missing_both)["errors"].size(), 2u) << missing_both.body;
  // The doc's predict example is the real answer's shape.
  const std::string example =
      "GET /api/v1/vehicles/sim-usim/predict?speed=1&dheading=-75&x=10&y=20&heading=45";
  const ApiResponse real = call(example_request(example));
  ASSERT_EQ(real.status, 200) << real.body;
  expect_example_matches(example, body(real));
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "1"}, {"dheading", "70"}, {"method", "model"}}))
                .status,
            404);  // no model yet
  const json missions = body(call(get("/api/v1/missions")));
  // When each ran, in wall-clock time, kept with it (for missions of earlier sessions).
  for (const auto& m : missions) {
    ASSERT_TRUE(m["started_utc"].is_string()) << m.dump();
    ASSERT_TRUE(m["ended_utc"].is_string()) << m.dump();
    EXPECT_LE(m["created_utc"].get<std::string>(), m["started_utc"].get<std::string>());
    EXPECT_LE(m["started_utc"].get<std::string>(), m["ended_utc"].get<std::string>());
  }
  const std::string missions_csv = call(get("/api/v1/missions", {{"format", "csv"}})).body;
  EXPECT_EQ(
      missions_csv.rfind("id,vehicle_id,name,status,created_utc,started_s,ended_s,started_utc,"
                         "ended_utc,turns_ok,",
                         0),
      0u)
      << missions_csv;
  EXPECT_NE(missions_csv.find("," + missions[0]["started_utc"].get<std::string>() + ","),
            std::string::npos);
  const ApiResponse fitted = call(
      post("/api/v1/vehicles/sim-usim/models",
           json{{"missions", {missions[0]["id"], missions[1]["id"]}}, {"history_s", 3}}.dump()));
  ASSERT_EQ(fitted.status, 201) << fitted.body;
  const auto model_id = body(fitted)["id"].get<std::int64_t>();
  EXPECT_EQ(body(call(get("/api/v1/models/" + std::to_string(model_id))))["history"], 12);
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/models"))).size(), 1u);
  const ApiResponse models_csv = call(get("/api/v1/vehicles/sim-usim/models", {{"format", "csv"}}));
  ASSERT_EQ(models_csv.status, 200);
  EXPECT_EQ(models_csv.body.rfind("id,created_utc,vehicle_id,form,history_samples,rate_hz,", 0), 0u)
      << models_csv.body;
  EXPECT_NE(models_csv.body.find("\n" + std::to_string(model_id) + ","), std::string::npos);
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/models", R"({"missions":[999]})")).status, 422);
  const json model = body(call(get("/api/v1/vehicles/sim-usim/predict",
                                   {{"speed", "1"}, {"dheading", "70"}, {"method", "model"}})));
  EXPECT_EQ(model["model_id"], model_id);
  // Replay's fair prediction: without a mission, the table of the other one's turns; the only
  // model was trained on both, so none answers; a bad id is named.
  const std::string first = missions[0]["id"].dump();
  const ApiResponse held_out =
      call(get("/api/v1/vehicles/sim-usim/predict",
               {{"speed", "1"}, {"dheading", "70"}, {"without_mission", first}}));
  ASSERT_EQ(held_out.status, 200) << held_out.body;
  EXPECT_EQ(body(held_out)["without_mission_id"], missions[0]["id"]);
  EXPECT_EQ(body(held_out)["table_source"], "turns");
  const auto a_turn =
      body(call(get("/api/v1/turns", {{"status", "ok"}, {"limit", "1"}})))["items"][0]["id"];
  const ApiResponse without_turn =
      call(get("/api/v1/vehicles/sim-usim/predict",
               {{"speed", "1"}, {"dheading", "70"}, {"without_turn", a_turn.dump()}}));
  ASSERT_EQ(without_turn.status, 200) << without_turn.body;
  EXPECT_EQ(body(without_turn)["without_turn_id"], a_turn);
  const ApiResponse no_fair_model = call(
      get("/api/v1/vehicles/sim-usim/predict",
          {{"speed", "1"}, {"dheading", "70"}, {"method", "model"}, {"without_mission", first}}));
  EXPECT_EQ(no_fair_model.status, 404) << no_fair_model.body;
  const ApiResponse bad_id =
      call(get("/api/v1/vehicles/sim-usim/predict",
               {{"speed", "1"}, {"dheading", "70"}, {"without_mission", "x"}}));
  EXPECT_EQ(bad_id.status, 400);
  EXPECT_EQ(body(bad_id)["parameter"], "without_mission") << bad_id.body;
  // The speed after is a parameter named in its error; equal to the speed it is
  // a constant-speed turn; the model flies a change with its speed model (or says it has none).
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "-1"}}))
                .status,
            400);
  const json same = body(call(get("/api/v1/vehicles/sim-usim/predict",
                                  {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "1"}})));
  EXPECT_FALSE(same.contains("speed_change_source"));
  const ApiResponse slowing =
      call(get("/api/v1/vehicles/sim-usim/predict",
               {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "0.5"}, {"method", "model"}}));
  if (slowing.status == 200) {
    EXPECT_EQ(body(slowing)["speed_change_source"], "model");
    EXPECT_EQ(body(slowing)["speed_after_mps"], 0.5);
  } else {
    EXPECT_EQ(slowing.status, 400) << slowing.body;
    EXPECT_NE(slowing.body.find("speed_after"), std::string::npos) << slowing.body;
  }
  const json comparison = body(call(get("/api/v1/vehicles/sim-usim/compare")));
  EXPECT_EQ(comparison["cells"].size(), 4u);
  EXPECT_EQ(comparison["model_id"], model_id);
  ApiRequest csv = get("/api/v1/vehicles/sim-usim/compare", {{"format", "csv"}});
  EXPECT_EQ(call(csv).body.rfind("speed_mps,dheading_deg,n_turns", 0), 0u);
}

TEST_F(StationApi, NavPagesConcatenateToTheStoredTrack) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const auto stored = avk::store::Store(db_.path()).navigation().for_mission(id);
  ASSERT_GT(stored.size(), 1000u);
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/nav";
  std::vector<json> rows;
  std::map<std::string, std::string> q = {{"limit", "400"}};
  int pages = 0;
  for (;;) {
    const ApiResponse r = call(get(path, q));
    ASSERT_EQ(r.status, 200) << r.body;
    const json page = body(r);
    ++pages;
    ASSERT_LE(page["items"].size(), 400u);
    for (const auto& item : page["items"])
      rows.push_back(item);
    if (page["next"].is_null()) break;
    q["after"] = page["next"].dump();
  }
  EXPECT_EQ(pages, static_cast<int>(stored.size() / 400 + 1));
  ASSERT_EQ(rows.size(), stored.size());
  // Insertion order is the recorder's time order for one run: the same rows as
  // navigation().for_mission.
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    EXPECT_EQ(rows[i]["t_s"].get<double>(), stored[i].t_s);
    EXPECT_EQ(rows[i]["x_m"].get<double>(), stored[i].x_m);
    EXPECT_EQ(rows[i]["helm_mode"].get<std::string>(), stored[i].helm_mode);
    for (const char* k :
         {"y_m", "heading_deg", "speed_mps", "desired_heading_deg", "desired_speed_mps"})
      EXPECT_TRUE(rows[i].contains(k)) << k;
  }
  // The track as CSV, paged by X-Next-After, is the same rows as the JSON pages.
  const auto split = [](const std::string& text, char sep) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream in(text);
    while (std::getline(in, cell, sep))
      out.push_back(cell);
    return out;
  };
  std::vector<std::string> csv_rows;
  std::map<std::string, std::string> cq = {{"limit", "400"}, {"format", "csv"}};
  for (int page = 0; page < 1000; ++page) {
    const ApiResponse r = call(get(path, cq));
    ASSERT_EQ(r.status, 200) << r.body;
    ASSERT_EQ(r.content_type.rfind("text/csv", 0), 0u);
    const auto lines = split(r.body, '\n');
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines[0],
              "t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,helm_mode");
    csv_rows.insert(csv_rows.end(), lines.begin() + 1, lines.end());
    const std::string next = header(r, "X-Next-After");
    if (next.empty()) break;
    cq["after"] = next;
  }
  ASSERT_EQ(csv_rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    const auto cells = split(csv_rows[i], ',');
    ASSERT_EQ(cells.size(), 8u) << csv_rows[i];
    EXPECT_EQ(std::stod(cells[0]), rows[i]["t_s"].get<double>());
    EXPECT_EQ(std::stod(cells[1]), rows[i]["x_m"].get<double>());
    EXPECT_EQ(std::stod(cells[3]), rows[i]["heading_deg"].get<double>());
    EXPECT_EQ(cells[5].empty(), rows[i]["desired_heading_deg"].is_null());
    EXPECT_EQ(cells[7], rows[i]["helm_mode"].get<std::string>());
  }
  // The event log likewise, with Accept instead of ?format=.
  const std::string events_path = "/api/v1/missions/" + std::to_string(id) + "/events";
  const json events = body(call(get(events_path, {{"limit", "1000"}})));
  ApiRequest events_csv = get(events_path, {{"limit", "1000"}});
  events_csv.accept = "text/csv";
  const auto event_lines = split(call(events_csv).body, '\n');
  ASSERT_EQ(event_lines.size(), events["items"].size() + 1);
  EXPECT_EQ(event_lines[0], "id,t_s,kind,message");
  for (std::size_t i = 0; i < events["items"].size(); ++i) {
    const json& e = events["items"][i];
    EXPECT_EQ(event_lines[i + 1].rfind(std::to_string(e["id"].get<std::int64_t>()) + ",", 0), 0u);
    EXPECT_NE(event_lines[i + 1].find("," + e["kind"].get<std::string>() + ","), std::string::npos);
  }
  ApiRequest vehicles_csv = get("/api/v1/vehicles");
  vehicles_csv.accept = "text/csv";
  const auto vehicle_lines = split(call(vehicles_csv).body, '\n');
  ASSERT_EQ(vehicle_lines.size(), 2u);
  EXPECT_EQ(vehicle_lines[0].rfind("id,kind,max_speed_mps,link,helm_mode,", 0), 0u);
  EXPECT_EQ(vehicle_lines[1].rfind("sim-usim,usim,", 0), 0u) << vehicle_lines[1];
  // The default page is 5000 rows.
  EXPECT_EQ(body(call(get(path)))["items"].size(), std::min<std::size_t>(stored.size(), 5000));
  EXPECT_EQ(call(get("/api/v1/missions/999/nav")).status, 404);
  for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
           {"limit", "0"}, {"limit", "10001"}, {"limit", "2.5"}, {"after", "-1"}, {"after", "x"}}) {
    const ApiResponse bad = call(get(path, {{k, v}}));
    EXPECT_EQ(bad.status, 400) << k << "=" << v;
    EXPECT_EQ(body(bad)["parameter"], k);
  }
}

TEST_F(StationApi, ModelHeadingsOneStepAndSimulated) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const ApiResponse fitted = call(
      post("/api/v1/vehicles/sim-usim/models", json{{"missions", {id}}, {"history_s", 3}}.dump()));
  ASSERT_EQ(fitted.status, 201) << fitted.body;
  const auto model_id = body(fitted)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/models/" + std::to_string(model_id) + "/headings";
  const ApiResponse r = call(get(path, {{"mission", std::to_string(id)}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_DOUBLE_EQ(h["dt_s"].get<double>(), 0.25);
  const std::size_t warmup = 13;  // 3 s at 4 Hz, + 1 for the invariant form's increments
  EXPECT_EQ(h["warmup_samples"], warmup);
  ASSERT_FALSE(h["segments"].empty());
  std::size_t total = 0, compared = 0;
  double one_sq = 0.0, sim_sq = 0.0;
  for (const auto& s : h["segments"]) {
    const std::size_t n = s["heading_deg"].size();
    total += n;
    for (const char* k : {"desired_heading_deg", "one_step_deg", "simulated_deg"})
      ASSERT_EQ(s[k].size(), n) << k;
    for (std::size_t k = 0; k < n; ++k) {
      if (k < warmup) {
        EXPECT_TRUE(s["one_step_deg"][k].is_null()) << k;
        EXPECT_TRUE(s["simulated_deg"][k].is_null()) << k;
        continue;
      }
      ASSERT_TRUE(s["one_step_deg"][k].is_number()) << k;
      ASSERT_TRUE(s["simulated_deg"][k].is_number()) << k;
      const double measured = s["heading_deg"][k].get<double>();
      one_sq += std::pow(s["one_step_deg"][k].get<double>() - measured, 2);
      sim_sq += std::pow(s["simulated_deg"][k].get<double>() - measured, 2);
      ++compared;
    }
  }
  EXPECT_LE(total, 2400u);
  ASSERT_GT(compared, 100u);
  // One step from measured history is the easier problem: it must be closer on average.
  EXPECT_LT(one_sq, sim_sq);
  EXPECT_LT(std::sqrt(one_sq / compared), 2.0);

  const json capped = body(call(get(path, {{"mission", std::to_string(id)}, {"limit", "50"}})));
  std::size_t capped_total = 0;
  for (const auto& s : capped["segments"])
    capped_total += s["heading_deg"].size();
  EXPECT_EQ(capped_total, std::min<std::size_t>(total, 50));
  EXPECT_EQ(capped["segments"][0]["heading_deg"],
            json(std::vector<double>(h["segments"][0]["heading_deg"].begin(),
                                     h["segments"][0]["heading_deg"].begin() +
                                         static_cast<long>(std::min<std::size_t>(
                                             50, h["segments"][0]["heading_deg"].size())))));

  EXPECT_EQ(call(get("/api/v1/models/999/headings", {{"mission", std::to_string(id)}})).status,
            404);
  EXPECT_EQ(call(get(path, {{"mission", "999"}})).status, 404);
  EXPECT_EQ(call(get(path)).status, 400);
  EXPECT_EQ(call(get(path, {{"mission", std::to_string(id)}, {"limit", "0"}})).status, 400);
  std::int64_t empty = 0;
  {
    avk::store::Store s(db_.path());
    empty = s.missions().create("sim-usim", "no nav", "{}");
  }
  const ApiResponse none = call(get(path, {{"mission", std::to_string(empty)}}));
  EXPECT_EQ(none.status, 422) << none.body;
}

// Harvesting is a write (the token always), and its counts come back; the CKT
// endpoints take include=collection|harvested.
TEST_F(StationApi, HarvestIsAControlEndpointAndTheTableSaysWhatItIncludes) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/harvest";
  EXPECT_EQ(call(post(path, "", "")).status, 401);
  const ApiResponse r = call(post(path, ""));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_EQ(h["mission_id"], id);
  EXPECT_GE(h["already_recorded"].get<int>(), 4);  // the mission's own turns, not twice
  EXPECT_EQ(h["steps"].get<int>(), h["harvested"].get<int>() + h["already_recorded"].get<int>() +
                                       h["rejected"].get<int>());
  EXPECT_EQ(h["rejected_by_reason"].size(), 13u);
  EXPECT_EQ(call(post("/api/v1/missions/999/harvest", "")).status, 404);
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt")))["include"], "collection");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "harvested"}})))["include"],
            "harvested");
  const ApiResponse bad = call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "all"}}));
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("include"), std::string::npos);
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "0.5"}, {"dheading", "40"}, {"include", "harvested"}}))
                .status,
            200);
}

}  // namespace
