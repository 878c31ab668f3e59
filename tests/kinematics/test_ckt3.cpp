// The CKT over (speed, heading change, initial yaw rate): slices, interpolation across the yaw
// rate, reflection, the model fill, and the turn record's initial yaw rate.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/angles.hpp"
#include "kinematics/ckt3.hpp"
#include "kinematics/ckt3_file.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/parse_error.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/yaw_model.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

// A turn of the slice at raw (clockwise +) initial yaw rate `raw_rate_dps`: an arc of radius R
// after a lead-in of L, whose advance is L + R sin(d) and transfer R (1 - cos(d)).
TurnSequence arc(double dheading_deg, double radius_m, std::optional<double> raw_rate_dps,
                 double lead_in_m = 1.0, unsigned seed = 1) {
  ArcTurnSpec s;
  s.speed_mps = 1.0;
  s.dheading_deg = dheading_deg;
  s.radius_m = radius_m;
  s.lead_in_m = lead_in_m;
  s.dt_s = 0.1;
  s.seed = seed;
  s.start = {10.0 * seed, -5.0 * seed, 37.0 * seed};
  TurnSequence t = make_arc_turn(s);
  t.meta().initial_yaw_rate_dps = raw_rate_dps;
  return t;
}

// Slices at -10, 0, +10 deg/s: radii 5, 4, 3 m (a turn begun against itself is wider), two turns
// a cell, both sides, at 45 and 90 deg.
std::vector<TurnSequence> three_slices() {
  std::vector<TurnSequence> turns;
  unsigned seed = 1;
  for (const auto& [rate, radius] : {std::pair{-10.0, 5.0}, {0.0, 4.0}, {10.0, 3.0}}) {
    for (double d : {45.0, 90.0}) {
      // Right turn: into the turn is clockwise (+); left turn: anticlockwise (-).
      turns.push_back(
          arc(d, radius, rate == 0.0 ? std::nullopt : std::optional(rate), 1.0, seed++));
      turns.push_back(
          arc(-d, radius, rate == 0.0 ? std::optional(0.3) : std::optional(-rate), 1.0, seed++));
    }
  }
  return turns;
}

// The three slices without the +10 deg/s slice's 45 deg turns: a cell for the model to fill.
std::vector<TurnSequence> without_slice_10_at_45() {
  std::vector<TurnSequence> turns;
  for (const auto& turn : three_slices()) {
    if (normalized_initial_yaw_rate_dps(turn) > 5.0 && std::abs(turn.meta().goal_dheading_deg) < 60)
      continue;
    turns.push_back(turn);
  }
  return turns;
}

// The heading of a trajectory's last segment, from its heading profile.
double end_heading_deg(const Polyline& p, double dheading_deg) {
  return heading_profile(p, dheading_deg).fraction.back() * dheading_deg;
}

}  // namespace

TEST(YawRateCkt, AssignsTurnsToSlicesByNormalisedInitialYawRate) {
  YawRateBuildReport report;
  const YawRateCkt t =
      YawRateCkt::build(three_slices(), std::nullopt, {}, std::nullopt, {}, &report);
  ASSERT_EQ(t.slices().size(), 3u);
  EXPECT_DOUBLE_EQ(t.slices()[0].initial_yaw_rate_dps, -10.0);
  EXPECT_DOUBLE_EQ(t.slices()[1].initial_yaw_rate_dps, 0.0);
  EXPECT_DOUBLE_EQ(t.slices()[2].initial_yaw_rate_dps, 10.0);
  EXPECT_EQ(report.turns_used, 12u);
  for (const auto& s : t.slices()) {
    for (const auto& c : s.table.cells())
      EXPECT_EQ(c.n_turns, 2u) << s.initial_yaw_rate_dps << " " << c.dheading_deg;
  }
  for (const auto& c : t.coverage()) {
    EXPECT_EQ(c.measured, 2u);
    EXPECT_EQ(c.model, 0u);
    EXPECT_EQ(c.empty, 0u);
  }
}

TEST(YawRateCkt, ExactSliceAnswersItsArc) {
  const YawRateCkt t = YawRateCkt::build(three_slices());
  for (const auto& [rate, radius] : {std::pair{-10.0, 5.0}, {0.0, 4.0}, {10.0, 3.0}}) {
    const YawRatePrediction p = t.query(1.0, 90.0, rate);
    EXPECT_EQ(p.source, CellSource::measured);
    EXPECT_FALSE(p.yaw_rate_clamped);
    EXPECT_NEAR(p.prediction.advance_m, 1.0 + radius, 0.05) << rate;
    EXPECT_NEAR(p.prediction.transfer_m, radius, 0.05) << rate;
  }
}

TEST(YawRateCkt, HalfwayBetweenSlicesBlendsThem) {
  const YawRateCkt t = YawRateCkt::build(three_slices());
  const YawRatePrediction p = t.query(1.0, 90.0, 5.0);
  EXPECT_EQ(p.source, CellSource::interpolated);
  EXPECT_FALSE(p.prediction.exact_cell);
  // Advance and transfer halfway between the slices' (4 + 1, 4) and (3 + 1, 3).
  EXPECT_NEAR(p.prediction.advance_m, 4.5, 0.05);
  EXPECT_NEAR(p.prediction.transfer_m, 3.5, 0.05);
  // The blend ends on the asked heading and its path lies between the two slices' paths.
  EXPECT_NEAR(angle180_deg(end_heading_deg(p.prediction.trajectory, 90.0) - 90.0), 0.0, 1e-6);
  const double lo = t.query(1.0, 90.0, 0.0).prediction.trajectory.back().x_m;
  const double hi = t.query(1.0, 90.0, 10.0).prediction.trajectory.back().x_m;
  EXPECT_GT(p.prediction.trajectory.back().x_m, std::min(lo, hi) - 1e-6);
  EXPECT_LT(p.prediction.trajectory.back().x_m, std::max(lo, hi) + 1e-6);
  // Between slices as the 2-D table is between heading changes: a 67.5 deg turn also ends on 67.5.
  const YawRatePrediction q = t.query(1.0, 67.5, -5.0);
  EXPECT_NEAR(angle180_deg(end_heading_deg(q.prediction.trajectory, 67.5) - 67.5), 0.0, 1e-6);
}

TEST(YawRateCkt, LeftTurnIntoTheTurnIsTheMirroredRightTurn) {
  const YawRateCkt t = YawRateCkt::build(three_slices());
  for (double rate : {-10.0, -4.0, 0.0, 7.0}) {
    const YawRatePrediction r = t.query(1.0, 60.0, rate);
    const YawRatePrediction l = t.query(1.0, -60.0, rate);
    ASSERT_EQ(r.prediction.trajectory.size(), l.prediction.trajectory.size());
    for (std::size_t i = 0; i < r.prediction.trajectory.size(); ++i) {
      EXPECT_DOUBLE_EQ(l.prediction.trajectory[i].x_m, -r.prediction.trajectory[i].x_m);
      EXPECT_DOUBLE_EQ(l.prediction.trajectory[i].y_m, r.prediction.trajectory[i].y_m);
    }
    EXPECT_DOUBLE_EQ(l.prediction.advance_m, r.prediction.advance_m);
  }
  // A left turn begun turning anticlockwise (raw -10 deg/s) is a turn into itself: slice +10.
  const TurnSequence left = arc(-90.0, 3.0, -10.0);
  EXPECT_DOUBLE_EQ(normalized_initial_yaw_rate_dps(left), 10.0);
  EXPECT_DOUBLE_EQ(*left.normalized().meta().initial_yaw_rate_dps, 10.0);
}

TEST(YawRateCkt, OutsideTheYawRateRangeIsClampedAndFlagged) {
  const YawRateCkt t = YawRateCkt::build(three_slices());
  const YawRatePrediction p = t.query(1.0, 90.0, 25.0);
  EXPECT_TRUE(p.yaw_rate_clamped);
  EXPECT_NEAR(p.prediction.advance_m, t.query(1.0, 90.0, 10.0).prediction.advance_m, 1e-12);
  EXPECT_TRUE(t.query(1.0, 90.0, -12.0).yaw_rate_clamped);
  EXPECT_THROW(t.query(1.0, 90.0, std::nan("")), std::invalid_argument);
  EXPECT_THROW(t.query(3.0, 90.0, 0.0), CktRangeError);
}

TEST(YawRateCkt, TheTwoDimensionalTableIsTheSteadySlice) {
  std::vector<TurnSequence> steady;
  for (const auto& turn : three_slices())
    if (std::abs(normalized_initial_yaw_rate_dps(turn)) < 1.0) steady.push_back(turn);
  const Ckt flat = Ckt::build(steady);
  const YawRateCkt t = YawRateCkt::build(three_slices());
  ASSERT_NE(t.steady(), nullptr);
  const TurnPrediction a = flat.query(1.0, 70.0);
  const TurnPrediction b = t.query(1.0, 70.0, 0.0).prediction;
  EXPECT_EQ(a.trajectory, b.trajectory);
  const YawRateCkt from_flat = YawRateCkt::from_table(flat);
  ASSERT_EQ(from_flat.slices().size(), 1u);
  // Asked with any yaw rate, a table with only the steady slice answers from it, flagged.
  const YawRatePrediction c = from_flat.query(1.0, 70.0, 6.0);
  EXPECT_TRUE(c.yaw_rate_clamped);
  EXPECT_EQ(c.prediction.trajectory, a.trajectory);
}

TEST(YawRateCkt, ModelFillMarksItsCells) {
  // Slice +10 has only 90 deg turns: its 45 deg cell is filled by the "model" (an arc of 2 m).
  const std::vector<TurnSequence> turns = without_slice_10_at_45();
  YawRateCkt t = YawRateCkt::build(turns);
  EXPECT_EQ(t.coverage()[2].empty, 1u);
  EXPECT_EQ(t.query(1.0, 45.0, 10.0).source, CellSource::interpolated);
  int calls = 0;
  t.fill([&](double u, double d, double rate) -> std::optional<TurnSequence> {
    ++calls;
    EXPECT_DOUBLE_EQ(u, 1.0);
    EXPECT_DOUBLE_EQ(d, 45.0);
    EXPECT_DOUBLE_EQ(rate, 10.0);
    return arc(d, 2.0, rate);
  });
  EXPECT_EQ(calls, 1);
  const auto cov = t.coverage();
  EXPECT_EQ(cov[2].model, 1u);
  EXPECT_EQ(cov[2].measured, 1u);
  EXPECT_EQ(cov[2].empty, 0u);
  const YawRatePrediction p = t.query(1.0, 45.0, 10.0);
  EXPECT_EQ(p.source, CellSource::model);
  EXPECT_NEAR(p.prediction.advance_m, 1.0 + 2.0 * std::sin(deg_to_rad(45.0)), 0.05);
  EXPECT_EQ(t.query(1.0, 90.0, 10.0).source, CellSource::measured);
}

TEST(YawRateCkt, FromSlicesRefusesMismatchedSlices) {
  const YawRateCkt t = YawRateCkt::build(three_slices());
  std::vector<YawRateSlice> same = {t.slices()[0], t.slices()[0]};
  EXPECT_THROW(YawRateCkt::from_slices(same), std::invalid_argument);
  std::vector<YawRateSlice> short_sources = {t.slices()[1]};
  short_sources[0].sources.pop_back();
  EXPECT_THROW(YawRateCkt::from_slices(short_sources), std::invalid_argument);
}

TEST(TurnJsonInitialYawRate, RoundTripsAndStaysAbsentWhenEmpty) {
  TurnSequence t = arc(-45.0, 3.0, -6.5);
  const TurnSequence back = turn_from_json(to_json(t));
  ASSERT_TRUE(back.meta().initial_yaw_rate_dps);
  EXPECT_DOUBLE_EQ(*back.meta().initial_yaw_rate_dps, -6.5);
  t.meta().initial_yaw_rate_dps.reset();
  const auto j = to_json(t);
  EXPECT_FALSE(j.contains("initial_yaw_rate_dps"));
  EXPECT_FALSE(turn_from_json(j).meta().initial_yaw_rate_dps);
}

TEST(TurningHistory, TheModelKeepsTurningAtTheRate) {
  for (YawModelForm form : {YawModelForm::invariant, YawModelForm::thesis}) {
    YawModel m;
    m.form = form;
    m.history = 2;
    m.rate_hz = 4.0;
    m.error_coeffs = {0.08, 0.02};
    m.heading_coeffs = form == YawModelForm::invariant ? std::vector<double>{0.6, 0.1}
                                                       : std::vector<double>{1.5, -0.5};
    const YawHistory h = turning_history(m, 30.0, 8.0);
    ASSERT_EQ(h.heading_deg.size(), m.warmup());
    EXPECT_DOUBLE_EQ(h.heading_deg.back(), 30.0);
    // Holding the history's desired heading offset, the first predicted step is at the rate.
    PredictOptions o;
    o.steps = 1;
    const auto steps = predict(m, h, h.desired_heading_deg.back(), {0.0, 0.0, 30.0}, 1.0, o);
    ASSERT_EQ(steps.size(), 2u);
    EXPECT_NEAR(steps[1].heading_deg - steps[0].heading_deg, 8.0 * m.dt_s(), 1e-9)
        << to_string(form);
  }
}

TEST(YawRateCktFile, RoundTripsSlicesAndSources) {
  const std::vector<TurnSequence> turns = without_slice_10_at_45();
  YawRateCkt t = YawRateCkt::build(turns);
  t.fill([&](double, double d, double rate) -> std::optional<TurnSequence> {
    return arc(d, 2.0, rate);
  });
  const nlohmann::json doc = yaw_rate_ckt_to_json(t);
  EXPECT_EQ(doc["schema_version"], 4);
  // The 2-D cells are the measured steady slice: a 2-D reader sees the table it always did.
  EXPECT_EQ(doc["cells"].size(), 2u);
  const YawRateCkt back = parse_yaw_rate_ckt_json(yaw_rate_ckt_to_json_string(t));
  ASSERT_EQ(back.slices().size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(back.slices()[k].initial_yaw_rate_dps, t.slices()[k].initial_yaw_rate_dps);
    EXPECT_EQ(back.slices()[k].sources, t.slices()[k].sources) << k;
  }
  EXPECT_EQ(back.query(1.0, 45.0, 10.0).source, CellSource::model);
  for (double rate : {-10.0, -3.0, 0.0, 6.0, 10.0}) {
    EXPECT_NEAR(back.query(1.0, 70.0, rate).prediction.advance_m,
                t.query(1.0, 70.0, rate).prediction.advance_m, 1e-9)
        << rate;
  }
  // A 2-D reader of the same document.
  EXPECT_EQ(parse_ckt_json(doc.dump()).cells().size(), 2u);
}

TEST(YawRateCktFile, OlderFilesLoadAsTheSteadySlice) {
  std::vector<TurnSequence> steady;
  for (const auto& turn : three_slices())
    if (std::abs(normalized_initial_yaw_rate_dps(turn)) < 1.0) steady.push_back(turn);
  const Ckt flat = Ckt::build(steady);
  nlohmann::json doc = ckt_to_json(flat);
  doc.erase("frame");  // also a schema-4 field
  for (int schema : {3, 4}) {
    doc["schema_version"] = schema;
    const YawRateCkt t = yaw_rate_ckt_from_json(doc);
    ASSERT_EQ(t.slices().size(), 1u);
    ASSERT_NE(t.steady(), nullptr);
    EXPECT_EQ(t.query(1.0, 90.0, 0.0).source, CellSource::measured);
    EXPECT_NEAR(t.query(1.0, 90.0, 0.0).prediction.advance_m, flat.query(1.0, 90.0).advance_m,
                1e-9);
  }
  // Slices are a schema-4 field; a bad source names its field.
  nlohmann::json with = yaw_rate_ckt_to_json(YawRateCkt::build(three_slices()));
  with.erase("frame");
  with["schema_version"] = 3;
  try {
    yaw_rate_ckt_from_json(with);
    FAIL() << "slices in schema 3 must be refused";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "/yaw_rate_slices");
  }
  with["schema_version"] = 4;
  with["yaw_rate_slices"][1]["cells"][0]["source"] = "guessed";
  try {
    yaw_rate_ckt_from_json(with);
    FAIL() << "an unknown source must be refused";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "/yaw_rate_slices/1/cells/0/source");
  }
  with["yaw_rate_slices"][1]["cells"][0]["source"] = "model";
  with["yaw_rate_slices"][1]["cells"][0]["n_turns"] = 0;
  try {
    yaw_rate_ckt_from_json(with);
    FAIL() << "a bad cell must be refused";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.field(), "/yaw_rate_slices/1/cells/0/n_turns");
  }
}
