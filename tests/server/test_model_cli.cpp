// avk model fit|sweep|list|show, avk compare and avk predict on simulated missions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "server/cli/cli.hpp"
#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/temp_db.hpp"

using nlohmann::json;

namespace {

using avk::testing::example;
using avk::testing::run;
using Result = avk::testing::CliResult;

// Two Figure 4-1 missions (two turns a cell) and the persistent-excitation mission, once for the
// whole suite.
class ModelCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    db_ = new avk::testing::TempDb("avk_model_cli");
    for (const char* seed : {"1", "2"}) {
      ASSERT_EQ(
          run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_->path(),
               "--sim", "--sim-config", example("sim-choppy.json"), "--seed", seed, "--quiet"})
              .rc,
          0);
    }
    ASSERT_EQ(run({"mission", "run", "--config", example("persistent-excitation.json"), "--db",
                   db_->path(), "--sim", "--sim-config", example("sim-choppy.json"), "--quiet"})
                  .rc,
              0);
  }
  static void TearDownTestSuite() { delete db_; }
  static avk::testing::TempDb* db_;
};
avk::testing::TempDb* ModelCli::db_ = nullptr;

TEST_F(ModelCli, FitStoresTheModelWithItsValidationErrors) {
  const Result r = run({"model", "fit", "--db", db_->path(), "--mission", "3", "--form", "thesis",
                        "--history", "5"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("thesis form, 20 samples"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("40 coefficients"), std::string::npos) << r.out;
  avk::store::Store s(db_->path());
  const auto m = s.models().latest();
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->model.form, avk::kinematics::YawModelForm::thesis);
  EXPECT_EQ(m->model.history, 20u);
  EXPECT_EQ(m->training_missions, std::vector<std::int64_t>{3});
  ASSERT_TRUE(m->validation_mse_m2.has_value());
  EXPECT_GT(*m->validation_mse_m2, 0.0);
  const Result shown =
      run({"model", "show", "--db", db_->path(), "--model", std::to_string(m->id)});
  ASSERT_EQ(shown.rc, 0);
  EXPECT_EQ(json::parse(shown.out)["error_coeffs"].size(), 20u);
}

TEST_F(ModelCli, BadOptionsNameTheProblem) {
  EXPECT_EQ(run({"model", "fit", "--db", db_->path(), "--mission", "3", "--form", "nomoto"}).rc, 2);
  EXPECT_EQ(run({"model", "fit", "--db", db_->path()}).rc, 2);  // no training mission
  const Result unknown = run({"model", "fit", "--db", db_->path(), "--mission", "99"});
  EXPECT_EQ(unknown.rc, 1);
  EXPECT_NE(unknown.err.find("no mission 99"), std::string::npos);
  EXPECT_EQ(run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "270"}).rc, 2);
  EXPECT_EQ(
      run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "90", "--method", "guess"})
          .rc,
      2);
  const Result no_model = run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "90",
                               "--method", "model", "--model", "999"});
  EXPECT_EQ(no_model.rc, 1);
  EXPECT_NE(no_model.err.find("no model 999"), std::string::npos);
  EXPECT_EQ(run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "90",
                 "--without-mission", "0.5"})
                .rc,
            2);
  const Result no_mission = run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "90",
                                 "--without-mission", "99"});
  EXPECT_EQ(no_mission.rc, 1);
  EXPECT_NE(no_mission.err.find("no mission 99"), std::string::npos) << no_mission.err;
}

TEST_F(ModelCli, CompareScoresEveryCellWithTwoTurns) {
  ASSERT_EQ(run({"model", "fit", "--db", db_->path(), "--mission", "3"}).rc, 0);
  const Result r = run({"compare", "--db", db_->path(), "--format", "json"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["cells"].size(), 18u);
  for (const auto& c : j["cells"]) {
    EXPECT_EQ(c["n_turns"], 2);
    ASSERT_TRUE(c["model"].is_object());
    EXPECT_GE(c["avk"]["mse_m2"].get<double>(), 0.0);
    EXPECT_GE(c["model"]["mse_m2"].get<double>(), 0.0);
    // Large turns are far from the instantaneous ray: AVK is no worse there (a cell whose turns
    // never get past x = 0 on the y(x) grid scores 0 for every method alike).
    if (c["dheading_deg"].get<double>() >= 100.0) {
      EXPECT_LE(c["avk"]["mse_m2"].get<double>(), c["instantaneous"]["mse_m2"].get<double>());
    }
  }
  // The fair table: every method on held-out turns, by path distance (m) and y(x) MSE.
  ASSERT_EQ(j["predictive"]["cells"].size(), 18u);
  double large_avk_m = 0.0, large_instantaneous_m = 0.0;
  for (const auto& c : j["predictive"]["cells"]) {
    EXPECT_EQ(c["n_turns"], 2);
    EXPECT_GE(c["avk"]["path_m"]["mean"].get<double>(), 0.0);
    ASSERT_TRUE(c["model"].is_object());
    // At 0.5 m/s in sim-choppy.json's 5 m/s wind the integral-free heading loop of the M200
    // (docs/sim-config.md) takes 20 m or more to come round against the wind, and with two turns
    // a cell one turn is a poor prediction of the other: the large turns are held to the
    // instantaneous ray at 1.0 and 1.5 m/s, and over all speeds together.
    if (c["dheading_deg"].get<double>() >= 100.0) {
      large_avk_m += c["avk"]["path_m"]["mean"].get<double>();
      large_instantaneous_m += c["instantaneous"]["path_m"]["mean"].get<double>();
      if (c["speed_mps"].get<double>() >= 1.0) {
        EXPECT_LT(c["avk"]["path_m"]["mean"].get<double>(),
                  c["instantaneous"]["path_m"]["mean"].get<double>());
      }
    }
  }
  EXPECT_LT(large_avk_m, large_instantaneous_m);
  const Result csv = run(
      {"compare", "--db", db_->path(), "--format", "csv", "--no-model", "--scoring", "in_sample"});
  ASSERT_EQ(csv.rc, 0);
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 19);
  const Result fair_csv = run({"compare", "--db", db_->path(), "--format", "csv"});
  ASSERT_EQ(fair_csv.rc, 0);
  EXPECT_EQ(fair_csv.out.rfind("speed_mps,dheading_deg,n_turns,span_m,avk_path_m", 0), 0u);
  const Result table = run({"compare", "--db", db_->path()});
  EXPECT_NE(table.out.find("mean distance at equal arc length"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("median:"), std::string::npos);
  const Result thesis = run({"compare", "--db", db_->path(), "--scoring", "in_sample"});
  EXPECT_NE(thesis.out.find("AVK m^2"), std::string::npos) << thesis.out;
  EXPECT_EQ(run({"compare", "--db", db_->path(), "--metric", "feet"}).rc, 2);
}

TEST_F(ModelCli, PredictEachMethodPlacedAtAPose) {
  ASSERT_EQ(run({"model", "fit", "--db", db_->path(), "--mission", "3"}).rc, 0);
  ASSERT_EQ(run({"ckt", "build", "--db", db_->path(), "--mission", "1", "--mission", "2", "--out",
                 db_->path() + ".ckt.json"})
                .rc,
            0);
  for (const char* method : {"avk", "model", "instantaneous"}) {
    // Through the water (the missions left the station an estimate of their current, which a
    // prediction over ground would add the same way to either side).
    const Result right = run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "70",
                              "--method", method, "--current", "none"});
    const Result left = run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "-70",
                             "--method", method, "--current", "none"});
    ASSERT_EQ(right.rc, 0) << method << right.err;
    ASSERT_EQ(left.rc, 0) << method << left.err;
    const auto r = json::parse(right.out)["trajectory"];
    const auto l = json::parse(left.out)["trajectory"];
    ASSERT_GE(r.size(), 2u) << method;
    ASSERT_EQ(r.size(), l.size()) << method;
    // A left turn is the mirror image of the right one; both start at the origin heading north.
    for (std::size_t i = 0; i < r.size(); ++i) {
      EXPECT_NEAR(l[i][0].get<double>(), -r[i][0].get<double>(), 1e-9) << method;
      EXPECT_NEAR(l[i][1].get<double>(), r[i][1].get<double>(), 1e-9) << method;
    }
    EXPECT_GT(r.back()[0].get<double>(), 0.0) << method;  // ends to starboard
    // Placed at a pose: starts there.
    const Result placed = run({"predict", "--db", db_->path(), "--speed", "1", "--dheading", "70",
                               "--method", method, "--x", "10", "--y", "-5", "--heading", "90"});
    const auto p = json::parse(placed.out)["trajectory"];
    EXPECT_NEAR(p[0][0].get<double>(), 10.0, 1e-9);
    EXPECT_NEAR(p[0][1].get<double>(), -5.0, 1e-9);
  }
}

TEST_F(ModelCli, SweepReportsEveryHistoryLength) {
  const Result r =
      run({"model", "sweep", "--db", db_->path(), "--mission", "3", "--format", "csv"});
  ASSERT_EQ(r.rc, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("history_s,", 0), 0u);
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    EXPECT_NE(line.find(','), std::string::npos);
  }
  EXPECT_EQ(rows, 10);  // 2 s to 20 s
}

}  // namespace

namespace {
TEST_F(ModelCli, SpeedModelChangesThePredictedPath) {
  ASSERT_EQ(run({"model", "fit", "--db", db_->path(), "--mission", "3"}).rc, 0);
  const auto path = [&](bool speed_model) {
    std::vector<std::string> args = {"predict",    "--db", db_->path(), "--speed", "1.5",
                                     "--dheading", "90",   "--method",  "model"};
    if (speed_model) args.push_back("--speed-model");
    const Result r = run(args);
    EXPECT_EQ(r.rc, 0) << r.err;
    return json::parse(r.out);
  };
  const json constant = path(false), modelled = path(true);
  EXPECT_FALSE(constant["speed_model"].get<bool>());
  EXPECT_TRUE(modelled["speed_model"].get<bool>());
  // The same headings, a different speed through the turn: the end points differ.
  const auto& a = constant["trajectory"].back();
  const auto& b = modelled["trajectory"].back();
  EXPECT_GT(
      std::hypot(a[0].get<double>() - b[0].get<double>(), a[1].get<double>() - b[1].get<double>()),
      1e-3);
}
}  // namespace
