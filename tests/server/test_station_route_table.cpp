// The station's route table against docs/api.md and the rules every route shares: documented,
// CSV where served, content negotiation, the work each answer takes, and 405 before the token.
#include <gtest/gtest.h>

#include "server/station_api_fixture.hpp"

namespace {

using namespace avk::testing::station_api;

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

}  // namespace
