// `avk predict` and GET /vehicles/{vid}/predict answer the same question with the same
// trajectory, whatever the database holds: a vehicle with turns, a vehicle with only an imported
// CKT, and two vehicles side by side (a table imported last for one must not answer for the
// other). Both front ends call the one predict use case.
#include <gtest/gtest.h>

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
};

class PredictParity : public ::testing::Test {
 protected:
  json over_http(const Question& q) {
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
    const auto res = station.handle(r);
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
    kinematics::Ckt t = kinematics::Ckt::build(db.load_normalized_turns({}, donor));
    t.vehicle_id = vid;
    db.save_ckt_snapshot(t, {});
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

}  // namespace
