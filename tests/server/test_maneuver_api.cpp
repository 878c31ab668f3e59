// The maneuver endpoints (POST /vehicles/{vid}/maneuvers/evaluate and /simulate, GET
// .../maneuvers/ongoing) and `avk maneuver`, over a database of analytic arc turns, called
// without sockets. The instantaneous method is checked against the closed form of a head-on
// encounter; the errors name the field; the questions are open on loopback like the reads.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "server/station.hpp"
#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/sim_station.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
using nlohmann::json;

constexpr const char* kToken = "maneuver-test-token";
constexpr double kPi = 3.14159265358979323846;

// Own vehicle at the origin heading north at 1 m/s; a contact 40 m ahead coming south at 1 m/s.
// On the ray of heading change psi the CPA is 40 sin(psi / 2) at t = 20 s, so the smallest turn
// that clears 10 m is 28.96 deg: 30 deg on the 5-deg grid, with a CPA of 40 sin 15 deg.
json head_on(const std::string& method = "instantaneous") {
  return {{"own", {{"x_m", 0.0}, {"y_m", 0.0}, {"heading_deg", 0.0}, {"speed_mps", 1.0}}},
          {"contacts", {{{"x_m", 0.0}, {"y_m", 40.0}, {"course_deg", 180.0}, {"speed_mps", 1.0}}}},
          {"standoff_m", 10.0},
          {"horizon_s", 120.0},
          {"method", method}};
}

class ManeuverApi : public ::testing::Test {
 protected:
  void SetUp() override {
    store::Store db(db_.path());
    avk::testing::store_arc_turns(db, "boat");
  }

  server::StationOptions options() const {
    server::StationOptions o;
    o.db_path = db_.path();
    o.token = kToken;
    o.server_version = "test";
    return o;
  }

  server::ApiResponse call(const server::ApiRequest& r) {
    if (!station_) station_ = std::make_unique<server::Station>(options(), hub_);
    return station_->handle(r);
  }

  static server::ApiRequest post(const std::string& what, const std::string& body,
                                 const std::string& vehicle = "boat") {
    server::ApiRequest r;
    r.method = "POST";
    r.path = "/api/v1/vehicles/" + vehicle + "/maneuvers/" + what;
    r.body = body;
    r.content_type = "application/json";
    return r;
  }

  static server::ApiRequest get_ongoing(std::map<std::string, std::string> query) {
    server::ApiRequest r;
    r.method = "GET";
    r.path = "/api/v1/vehicles/boat/maneuvers/ongoing";
    r.query = std::move(query);
    return r;
  }

  // The response of a request that must succeed, as JSON.
  json ok(const server::ApiRequest& r) {
    const auto res = call(r);
    EXPECT_EQ(res.status, 200) << res.body;
    return json::parse(res.body);
  }

  // A 422 whose pointer names the field.
  void expect_field_error(const json& body, const std::string& pointer) {
    const auto res = call(post("evaluate", body.dump()));
    EXPECT_EQ(res.status, 422) << res.body;
    EXPECT_EQ(res.content_type, "application/problem+json");
    const json p = json::parse(res.body);
    EXPECT_EQ(p["pointer"], pointer) << p.dump();
    EXPECT_NE(p["detail"].get<std::string>().find(pointer), std::string::npos) << p.dump();
  }

  avk::testing::TempDb db_{"avk_maneuver_api"};
  server::StreamHub hub_;
  std::unique_ptr<server::Station> station_;
};

TEST_F(ManeuverApi, InstantaneousChoiceIsTheClosedFormOfAHeadOnEncounter) {
  // The corridor rule: the smallest heading change that clears (the default chooses by risk).
  json body = head_on();
  body["rule"] = "corridor";
  const json e = ok(post("evaluate", body.dump()));
  EXPECT_EQ(e["method"], "instantaneous");
  ASSERT_EQ(e["candidates"].size(), 73u);  // -180..180 in 5-deg steps
  ASSERT_TRUE(e["chosen"].is_object()) << e["chosen"];
  EXPECT_DOUBLE_EQ(e["chosen"]["dheading_deg"].get<double>(), 30.0);
  const json& c = e["candidates"][e["chosen"]["index"].get<std::size_t>()];
  EXPECT_NEAR(c["min_cpa_m"].get<double>(), 40.0 * std::sin(15.0 * kPi / 180.0), 1e-6);
  EXPECT_NEAR(c["contacts"][0]["cpa"]["time_s"].get<double>(), 20.0, 1e-6);
  EXPECT_TRUE(c["clears"].get<bool>());
  EXPECT_TRUE(c["contacts"][0]["edge_cpa"].is_null());  // a ray has no corridor
  // Every candidate: the closed form, and the path as [t, x, y] from the origin.
  for (const json& k : e["candidates"]) {
    const double psi = k["dheading_deg"].get<double>();
    EXPECT_NEAR(k["min_cpa_m"].get<double>(), 40.0 * std::abs(std::sin(psi * kPi / 360.0)), 1e-6)
        << psi;
    ASSERT_GE(k["path"].size(), 2u);
    EXPECT_EQ(k["path"][0], json({0.0, 0.0, 0.0}));
    EXPECT_EQ(k["path"][0].size(), 3u);
  }
  // Straight on: the contact is met head on.
  EXPECT_NEAR(e["candidates"][36]["min_cpa_m"].get<double>(), 0.0, 1e-9);
  EXPECT_FALSE(e["candidates"][36]["clears"].get<bool>());
}

TEST_F(ManeuverApi, AvkAnswersFromTheTurnsWithCorridorsAndTimes) {
  json body = head_on("avk");
  body["candidate_step_deg"] = 10.0;
  const json e = ok(post("evaluate", body.dump()));
  EXPECT_EQ(e["method"], "avk");
  EXPECT_EQ(e["table_source"], "turns");
  EXPECT_TRUE(e["timed_by_turns"].get<bool>());
  ASSERT_EQ(e["candidates"].size(), 37u);
  ASSERT_TRUE(e["chosen"].is_object()) << e.dump();
  const json& c = e["candidates"][e["chosen"]["index"].get<std::size_t>()];
  EXPECT_TRUE(c["clears"].get<bool>());
  // With corridors the choice is judged by the nearer edge.
  ASSERT_TRUE(c["min_edge_cpa_m"].is_number()) << c.dump();
  EXPECT_GE(c["min_edge_cpa_m"].get<double>(), 10.0);
  EXPECT_LE(c["min_edge_cpa_m"].get<double>(), c["min_cpa_m"].get<double>());
  ASSERT_TRUE(c["half_width_m"].is_array());
  EXPECT_EQ(c["half_width_m"].size(), c["path"].size());
  // Thinned to one point per 0.5 s, times increasing to the horizon.
  const json& path = c["path"];
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
    EXPECT_GE(path[i][0].get<double>() - path[i - 1][0].get<double>(), 0.5 - 1e-9);
  EXPECT_NEAR(path.back()[0].get<double>(), 120.0, 1e-6);
}

TEST_F(ManeuverApi, TheEvaluationWrittenCandidateByCandidateIsOneCanonicalDocument) {
  // The answer is written one candidate at a time into the rest of the document: parsed and
  // dumped again it is the same bytes (every candidate in place, keys in order, nothing lost),
  // with two contacts and a chosen candidate.
  json body = head_on("avk");
  body["candidate_step_deg"] = 15.0;
  body["contacts"].push_back(
      {{"x_m", 30.0}, {"y_m", 10.0}, {"course_deg", 270.0}, {"speed_mps", 0.8}});
  const auto r = call(post("evaluate", body.dump()));
  ASSERT_EQ(r.status, 200) << r.body;
  const json e = json::parse(r.body);
  EXPECT_EQ(e.dump(), r.body);
  ASSERT_GT(e["candidates"].size(), 2u);
  ASSERT_TRUE(e["chosen"].is_object());
  EXPECT_EQ(e["candidates"].back()["contacts"].size(), 2u) << e["candidates"].back().dump();
}

TEST_F(ManeuverApi, ValidationErrorsNameTheFieldAndBadJsonIs400) {
  json speed = head_on();
  speed["contacts"][0]["speed_mps"] = -1.0;
  expect_field_error(speed, "/contacts/0/speed_mps");
  speed["contacts"][0]["speed_mps"] = "fast";
  expect_field_error(speed, "/contacts/0/speed_mps");
  json unknown = head_on();
  unknown["contacts"][0]["colour"] = "red";
  expect_field_error(unknown, "/contacts/0/colour");
  json missing = head_on();
  missing.erase("own");
  expect_field_error(missing, "/own");
  json method = head_on("psychic");
  expect_field_error(method, "/method");
  json horizon = head_on();
  horizon["horizon_s"] = 1e4;
  expect_field_error(horizon, "/horizon_s");
  // Every problem is listed, not only the first.
  json two = head_on();
  two["standoff_m"] = 0.0;
  two["contacts"][0].erase("x_m");
  const json p = json::parse(call(post("evaluate", two.dump())).body);
  ASSERT_EQ(p["errors"].size(), 2u) << p.dump();
  EXPECT_EQ(p["errors"][0]["field"], "/contacts/0/x_m");
  EXPECT_EQ(p["errors"][1]["field"], "/standoff_m");

  EXPECT_EQ(call(post("evaluate", "{\"own\": ")).status, 400);
  EXPECT_EQ(call(post("evaluate", "[1, 2]")).status, 400);
  auto text = post("evaluate", head_on().dump());
  text.content_type = "text/plain";
  EXPECT_EQ(call(text).status, 415);
  // A vehicle without turns cannot answer with AVK.
  EXPECT_EQ(call(post("evaluate", head_on("avk").dump(), "nobody")).status, 404);
}

TEST_F(ManeuverApi, QuestionsAreOpenOnLoopbackLikeTheReadsAndNeedTheTokenFromAfar) {
  // Loopback without a token: answered, and admitted from its header alone.
  auto local = post("evaluate", head_on().dump());
  EXPECT_EQ(call(local).status, 200);
  auto head = local;
  head.body.clear();
  EXPECT_FALSE(station_->admit(head).refusal.has_value());
  // A control POST on loopback still needs the token.
  auto fit = post("evaluate", R"({"missions":[1]})");
  fit.path = "/api/v1/vehicles/boat/models";
  EXPECT_EQ(call(fit).status, 401);
  // From another address the question is refused without the token, as a read is.
  auto read = get_ongoing({{"x", "0"},
                           {"y", "0"},
                           {"heading", "0"},
                           {"dheading", "90"},
                           {"speed", "1"},
                           {"elapsed", "5"},
                           {"method", "instantaneous"}});
  for (auto* r : {&local, &read}) {
    r->remote_is_loopback = false;
    EXPECT_EQ(call(*r).status, 401) << r->path;
    auto h = *r;
    h.body.clear();
    EXPECT_TRUE(station_->admit(h).refusal.has_value()) << r->path;
    r->authorization = std::string("Bearer ") + kToken;
    EXPECT_EQ(call(*r).status, 200) << r->path;
  }
}

TEST_F(ManeuverApi, OngoingGivesTheExpectedPointAndTheDeviation) {
  // On the ray east at 1 m/s: after 5 s at (5, 0); measured 1 m north of it.
  const json o = ok(get_ongoing({{"x", "0"},
                                 {"y", "0"},
                                 {"heading", "0"},
                                 {"dheading", "90"},
                                 {"speed", "1"},
                                 {"elapsed", "5"},
                                 {"mx", "5"},
                                 {"my", "1"},
                                 {"method", "instantaneous"}}));
  EXPECT_NEAR(o["expected"]["x_m"].get<double>(), 5.0, 1e-9);
  EXPECT_NEAR(o["expected"]["y_m"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(o["deviation_m"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(o["cross_track_m"].get<double>(), 1.0, 1e-9);
  EXPECT_TRUE(o["inside_corridor"].is_null());  // no corridor on a ray
  ASSERT_GE(o["remaining"].size(), 2u);
  EXPECT_NEAR(o["remaining"][0][0].get<double>(), 5.0, 1e-9);

  // AVK from the stored turns: a corridor, and whether the vehicle is inside it.
  const json a = ok(get_ongoing({{"x", "10"},
                                 {"y", "-5"},
                                 {"heading", "30"},
                                 {"dheading", "-100"},
                                 {"speed", "1"},
                                 {"elapsed", "3"},
                                 {"mx", "10"},
                                 {"my", "-2"}}));
  EXPECT_EQ(a["method"], "avk");
  EXPECT_TRUE(a["half_width_m"].is_number()) << a.dump();
  EXPECT_TRUE(a["inside_corridor"].is_boolean()) << a.dump();
  EXPECT_TRUE(a["deviation_m"].is_number());
  EXPECT_EQ(a["prediction"][0], json({0.0, 10.0, -5.0}));

  const auto missing = call(
      get_ongoing({{"x", "0"}, {"y", "0"}, {"heading", "0"}, {"dheading", "90"}, {"speed", "1"}}));
  EXPECT_EQ(missing.status, 400);
  EXPECT_EQ(json::parse(missing.body)["parameter"], "elapsed");
  const auto half = call(get_ongoing({{"x", "0"},
                                      {"y", "0"},
                                      {"heading", "0"},
                                      {"dheading", "90"},
                                      {"speed", "1"},
                                      {"elapsed", "1"},
                                      {"mx", "3"}}));
  EXPECT_EQ(json::parse(half.body)["parameter"], "my");
}

TEST_F(ManeuverApi, SimulateFliesTheManeuverAndCapsTheQuestion) {
  json body = head_on();
  body.erase("method");
  body["own"]["x_m"] = 100.0;  // the simulator starts at the origin; the answer is shifted back
  body["contacts"][0]["x_m"] = 100.0;
  body["dheading_deg"] = 60.0;
  body["horizon_s"] = 40.0;
  const json s = ok(post("simulate", body.dump()));
  // Not the station's simulated vehicle (this station has none): the M200's defaults.
  EXPECT_EQ(s["station_setup"], false);
  EXPECT_EQ(s["sim_vehicle"], "catamaran:m200");
  EXPECT_TRUE(s["note"].is_string());
  ASSERT_GE(s["track"].size(), 10u);
  EXPECT_NEAR(s["track"][0][1].get<double>(), 100.0, 1.0);
  EXPECT_NEAR(s["track"][0][2].get<double>(), 0.0, 1.0);
  ASSERT_EQ(s["cpa"].size(), 1u);
  // A 60-deg turn to starboard clears the head-on contact by metres, never by nothing.
  EXPECT_GT(s["min_cpa_m"].get<double>(), 1.0);
  EXPECT_EQ(s["violated"], s["min_cpa_m"].get<double>() < 10.0);

  json long_one = body;
  long_one["horizon_s"] = 1000.0;
  auto res = call(post("simulate", long_one.dump()));
  EXPECT_EQ(res.status, 422);
  EXPECT_EQ(json::parse(res.body)["pointer"], "/horizon_s");
  json crowd = body;
  crowd["contacts"] = json::array();
  for (int i = 0; i < 17; ++i)
    crowd["contacts"].push_back(body["contacts"][0]);
  res = call(post("simulate", crowd.dump()));
  EXPECT_EQ(json::parse(res.body)["pointer"], "/contacts");
}

TEST_F(ManeuverApi, SimulateUsesTheStationsSimulatedVehicle) {
  server::Station station(avk::testing::sim_station_options(db_.path(), kToken, 1.0), hub_);
  json body = head_on();
  body.erase("method");
  body["dheading_deg"] = 40.0;
  body["horizon_s"] = 30.0;
  const auto res = station.handle(post("simulate", body.dump(), "sim-usim"));
  ASSERT_EQ(res.status, 200) << res.body;
  const json s = json::parse(res.body);
  EXPECT_EQ(s["station_setup"], true);
  EXPECT_EQ(s["sim_vehicle"], "usim");
  EXPECT_FALSE(s.contains("note"));
}

TEST_F(ManeuverApi, CliPrintsTheChoiceAndTheSameDocumentAsTheApi) {
  const std::vector<std::string> args = {
      "maneuver",   "evaluate",   "--db", db_.path(), "--own",         "0,0,0,1", "--contact",
      "0,40,180,1", "--standoff", "10",   "--method", "instantaneous", "--rule",  "corridor"};
  const auto table = avk::testing::run(args);
  ASSERT_EQ(table.rc, 0) << table.err;
  // The closed form's choice under the corridor rule, with its risk and margin after it.
  EXPECT_NE(table.out.find("chosen: +30° (CPA 10.4 m, risk "), std::string::npos) << table.out;
  EXPECT_NE(table.out.find(", margin 0.4 m): the smallest heading change whose corridor edge "
                           "clears\n"),
            std::string::npos)
      << table.out;
  EXPECT_NE(table.out.find("<- chosen"), std::string::npos);
  auto json_args = args;
  json_args.insert(json_args.end(), {"--format", "json"});
  const auto j = avk::testing::run(json_args);
  ASSERT_EQ(j.rc, 0) << j.err;
  json question = head_on();
  question["rule"] = "corridor";
  json api = ok(post("evaluate", question.dump()));
  EXPECT_EQ(json::parse(j.out), api);

  auto bad = args;
  bad[7] = "0,40,180,-1";
  const auto err = avk::testing::run(bad);
  EXPECT_EQ(err.rc, 1);
  EXPECT_NE(err.err.find("/contacts/0/speed_mps"), std::string::npos) << err.err;

  const auto ongoing = avk::testing::run({"maneuver", "ongoing", "--db", db_.path(), "--start",
                                          "0,0,0", "--dheading", "90", "--speed", "1", "--elapsed",
                                          "5", "--measured", "5,1", "--method", "instantaneous"});
  ASSERT_EQ(ongoing.rc, 0) << ongoing.err;
  EXPECT_NE(ongoing.out.find("x 5.00 m, y 0.00 m"), std::string::npos) << ongoing.out;
  EXPECT_NE(ongoing.out.find("deviation 1.00 m"), std::string::npos) << ongoing.out;
}

}  // namespace
