// `avk predict` and GET /vehicles/{vid}/predict answer the same question with the same
// trajectory, whatever the database holds: a vehicle with turns, a vehicle with only an imported
// CKT, and two vehicles side by side (a table imported last for one must not answer for the
// other). Both front ends call the one predict use case.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "server/station.hpp"
#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
using nlohmann::json;

struct Question {
  std::string vehicle;
  double speed;
  double dheading;
  std::string method = "avk";
  // The current (live, none or EAST,NORTH) and the speed reference, when asked; empty: not.
  std::string current = "";
  std::string speed_reference = "";
};

class PredictParity : public ::testing::Test {
 protected:
  server::ApiResponse ask_http(const Question& q) {
    server::StationOptions o;
    o.db_path = db_.path();
    o.token = "parity-token";
    server::Station station(o, hub_);
    server::ApiRequest r;
    r.method = "GET";
    r.path = "/api/v1/vehicles/" + q.vehicle + "/predict";
    r.query = {{"speed", json(q.speed).dump()},
               {"dheading", json(q.dheading).dump()},
               {"method", q.method}};
    if (!q.current.empty()) r.query["current"] = q.current;
    if (!q.speed_reference.empty()) r.query["speed_reference"] = q.speed_reference;
    return station.handle(r);
  }
  json over_http(const Question& q) {
    const auto res = ask_http(q);
    EXPECT_EQ(res.status, 200) << res.body;
    return json::parse(res.body);
  }
  json over_cli(const Question& q, bool name_vehicle = true) {
    std::vector<std::string> args = {"predict",
                                     "--db",
                                     db_.path(),
                                     "--speed",
                                     json(q.speed).dump(),
                                     "--dheading",
                                     json(q.dheading).dump(),
                                     "--method",
                                     q.method};
    if (name_vehicle) args.insert(args.end(), {"--vehicle", q.vehicle});
    if (!q.current.empty()) args.insert(args.end(), {"--current", q.current});
    if (!q.speed_reference.empty())
      args.insert(args.end(), {"--speed-reference", q.speed_reference});
    const auto r = avk::testing::run(args);
    EXPECT_EQ(r.rc, 0) << r.err;
    return json::parse(r.out);
  }
  void expect_same(const Question& q, bool name_vehicle = true) {
    const json http = over_http(q);
    const json cli = over_cli(q, name_vehicle);
    ASSERT_TRUE(http["trajectory"].is_array());
    ASSERT_GE(http["trajectory"].size(), 2u);
    // Field for field: the same document, trajectory included, to the last bit.
    EXPECT_EQ(http, cli) << "http " << http.dump() << "\ncli  " << cli.dump();
  }
  void import_table_of(const std::string& donor, const std::string& vid) {
    store::Store db(db_.path());
    kinematics::Ckt t = kinematics::Ckt::build(db.turns().load_normalized({}, donor));
    t.vehicle_id = vid;
    db.ckt_snapshots().save(t, {});
  }

  avk::testing::TempDb db_{"avk_predict_parity"};
  server::StreamHub hub_;
};

TEST_F(PredictParity, AVehicleWithTurns) {
  {
    store::Store db(db_.path());
    avk::testing::store_arc_turns(db, "alpha");
  }
  for (const double d : {40.0, -100.0, 133.0})
    expect_same({"alpha", 1.2, d}, false);  // the database's only vehicle, also unnamed
  expect_same({"alpha", 1.0, -70.0, "instantaneous"});
}

TEST_F(PredictParity, AVehicleWithOnlyAnImportedTable) {
  {
    store::Store db(db_.path());
    avk::testing::store_arc_turns(db, "donor", 1.7);
  }
  import_table_of("donor", "bravo");
  const json http = over_http({"bravo", 1.0, 100.0});
  EXPECT_EQ(http["table_source"], "imported");
  for (const double d : {100.0, -45.0})
    expect_same({"bravo", 1.0, d});
}

TEST_F(PredictParity, TwoVehiclesEachAnsweredByTheirOwnTable) {
  {
    store::Store db(db_.path());
    avk::testing::store_arc_turns(db, "small", 1.0);
    avk::testing::store_arc_turns(db, "large", 2.0);
  }
  // The newest snapshot in the database is of another vehicle: it answers for neither.
  import_table_of("large", "third");
  for (const std::string vid : {"small", "large"})
    expect_same({vid, 1.5, 90.0});
  const json small = over_http({"small", 1.5, 90.0});
  const json large = over_http({"large", 1.5, 90.0});
  EXPECT_NEAR(large["advance_m"].get<double>() / small["advance_m"].get<double>(), 2.0, 0.1);
  EXPECT_EQ(small["table_source"], "turns");
}

// In a current: both front ends answer over ground by default with the station's estimate, say
// the frame, the current with its uncertainty and the speed reference, and take the same
// overrides (current=none: through the water; speed_reference).
TEST_F(PredictParity, ACurrentAndASpeedReferenceAnswerTheSameWayAndSaySo) {
  {
    store::Store db(db_.path());
    const std::int64_t mission = avk::testing::store_arc_turns(db, "alpha");
    store::StoredCurrent c;
    c.mission_id = mission;
    c.estimate.east_mps = 0.2;
    c.estimate.north_mps = 0.0;
    c.estimate.covariance = {0.0004, 0.0, 0.0001};  // 0.02 m/s east, 0.01 m/s north
    c.estimate.legs = 5;
    db.currents().save(c, {});
  }
  for (const std::string current : {"", "none", "live", "0,0.3"})
    for (const std::string reference : {"", "over_ground", "through_water"})
      expect_same({"alpha", 1.2, 100.0, "avk", current, reference});
  const json by_default = over_http({"alpha", 1.2, 100.0});
  EXPECT_EQ(by_default["frame"], "normalized");  // where it is placed: unchanged
  EXPECT_EQ(by_default["relative_to"], "ground");
  EXPECT_EQ(by_default["current"]["source"], "live");
  EXPECT_DOUBLE_EQ(by_default["current"]["east_mps"].get<double>(), 0.2);
  // The estimate's 1 sigma: along the current (east) and across it, as an angle.
  EXPECT_NEAR(by_default["current"]["speed_sd_mps"].get<double>(), 0.02, 1e-12);
  EXPECT_NEAR(by_default["current"]["toward_sd_deg"].get<double>(),
              std::atan2(0.01, 0.2) * 180.0 / 3.14159265358979323846, 1e-9);
  EXPECT_NEAR(by_default["current"]["east_sd_mps"].get<double>(), 0.02, 1e-12);
  EXPECT_EQ(by_default["speed_reference"], (json{{"value", "over_ground"}, {"source", "default"}}));
  const json through_water = over_http({"alpha", 1.2, 100.0, "avk", "none"});
  EXPECT_EQ(through_water["relative_to"], "water");
  EXPECT_EQ(through_water["current"], (json{{"source", "none"}}));
  EXPECT_NE(through_water["trajectory"], by_default["trajectory"]);
  const json carried = over_http({"alpha", 1.2, 100.0, "avk", "", "through_water"});
  EXPECT_EQ(carried["speed_reference"], (json{{"value", "through_water"}, {"source", "query"}}));
  EXPECT_NE(carried["trajectory"], by_default["trajectory"]);
  // The same over ground as asking for the estimate by name.
  EXPECT_EQ(over_http({"alpha", 1.2, 100.0, "avk", "live"})["trajectory"],
            by_default["trajectory"]);
}

TEST_F(PredictParity, ABadSpeedReferenceIsRefusedByBoth) {
  {
    store::Store db(db_.path());
    avk::testing::store_arc_turns(db, "alpha");
  }
  const auto res = ask_http({"alpha", 1.0, 90.0, "avk", "", "sideways"});
  EXPECT_EQ(res.status, 400);
  EXPECT_EQ(json::parse(res.body)["parameter"], "speed_reference") << res.body;
  const auto cli = avk::testing::run({"predict", "--db", db_.path(), "--speed", "1", "--dheading",
                                      "90", "--speed-reference", "sideways"});
  EXPECT_NE(cli.rc, 0);
  EXPECT_NE(cli.err.find("--speed-reference"), std::string::npos) << cli.err;
}

}  // namespace
