// The station's REST API for turns and CKT cells: keyset pages and CSV, export and import,
// predictions, models and comparisons, with docs/api.md's example answers checked against the real.
#include <gtest/gtest.h>

#include "server/station_api_fixture.hpp"

namespace {

using namespace avk::testing::station_api;

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

}  // namespace
