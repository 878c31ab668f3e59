// When a table's trajectory is passed: from the recorded turns' clocks, blended and stretched like
// the trajectory, and kept in the CKT file.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_timing.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using namespace avk::kinematics;

std::vector<TurnSequence> arc_turns(double speed_mps, double dheading_deg, double actual_speed_mps,
                                    int n) {
  std::vector<TurnSequence> out;
  for (int k = 0; k < n; ++k) {
    avk::testing::ArcTurnSpec s;
    s.speed_mps = actual_speed_mps;
    s.dheading_deg = k % 2 ? -dheading_deg : dheading_deg;
    s.lead_in_m = 1.0;
    s.radius_m = 3.0;
    s.dt_s = 0.1;
    s.tail_m = 2.0;
    s.seed = static_cast<unsigned>(k + 1);
    s.position_noise_m = 0.02;
    TurnSequence t = avk::testing::make_arc_turn(s);
    // What was commanded, not what was done.
    t.meta().commanded_speed_mps = speed_mps;
    out.push_back(t);
  }
  return out;
}

TEST(TurnTiming, ConstantSpeedTurnsArePassedAtTheirSpeed) {
  const Ckt table = Ckt::build(arc_turns(1.0, 90.0, 1.0, 4));
  const CktCell& c = table.cell(0, 0);
  ASSERT_TRUE(c.timing);
  EXPECT_NEAR(c.timing->length_m, arc_length_m(c.trajectory), 1e-9);
  for (std::size_t i = 0; i < kTimingStations; i += 10) {
    const double l = c.timing->length_m * static_cast<double>(i) / (kTimingStations - 1);
    EXPECT_NEAR(c.timing->time_s[i], l / 1.0, 0.15) << i;
  }
}

TEST(TurnTiming, AVehicleSlowerThanCommandedIsLaterAlongItsPath) {
  // Commanded 1 m/s, flown at 0.5: the same geometry, twice the time.
  const Ckt table = Ckt::build(arc_turns(1.0, 90.0, 0.5, 4));
  const CktCell& c = table.cell(0, 0);
  ASSERT_TRUE(c.timing);
  const double turn_length = 1.0 + 3.0 * std::numbers::pi / 2.0 + 2.0;
  EXPECT_NEAR(time_at_length_s(*c.timing, turn_length * 0.5, 1.0), turn_length * 0.5 / 0.5, 0.3);
  EXPECT_NEAR(time_at_length_s(*c.timing, turn_length - 0.2, 1.0), (turn_length - 0.2) / 0.5, 0.4);
  // Past the longest turn the table's run-on is at the commanded speed.
  const double end = c.timing->time_s.back();
  EXPECT_NEAR(time_at_length_s(*c.timing, c.timing->length_m + 3.0, 1.0), end + 3.0, 1e-9);
}

TEST(TurnTiming, ACurlingPathIsFollowedInOrder) {
  // A 180 deg turn whose mean passes close to its own lead-in on the way back.
  const StationedPath mean = [] {
    StationedPath p;
    const Polyline arc = avk::testing::circular_arc(1.0, 180.0, 0.05);
    double s = 0.0;
    for (std::size_t i = 0; i < arc.size(); ++i) {
      if (i) s += distance_m(arc[i - 1], arc[i]);
      p.s_m.push_back(s);
      p.points.push_back(arc[i]);
    }
    return p;
  }();
  const auto t = timing_of(mean, 1.0, mean.points);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->time_s.back(), mean.s_m.back(), 1e-6);
  EXPECT_NEAR(t->time_s[50], mean.s_m.back() / 2.0, 0.03);
  for (std::size_t i = 1; i < kTimingStations; ++i)
    EXPECT_GE(t->time_s[i], t->time_s[i - 1]);
  EXPECT_FALSE(timing_of(mean, 0.0, mean.points));
}

TEST(TurnTiming, BlendedAndStretchedLikeTheTrajectory) {
  const TurnTiming a = constant_speed_timing(10.0, 1.0), b = constant_speed_timing(20.0, 0.5);
  const std::optional<TurnTiming> oa = a, ob = b, none;
  const auto m = blend_timings({{&oa, 0.5}, {&ob, 0.5}});
  ASSERT_TRUE(m);
  EXPECT_NEAR(m->length_m, 15.0, 1e-12);
  EXPECT_NEAR(m->time_s.back(), 25.0, 1e-12);
  EXPECT_FALSE(blend_timings({{&oa, 0.5}, {&none, 0.5}}));
  const TurnTiming s = scaled_timing(a, 15.0);
  EXPECT_NEAR(s.time_s.back(), 15.0, 1e-12);
  EXPECT_NEAR(time_at_length_s(s, 7.5, 1.0), 7.5, 1e-12);
}

TEST(TurnTiming, QueriesBetweenCellsCarryABlendedTiming) {
  std::vector<TurnSequence> turns = arc_turns(1.0, 60.0, 1.0, 3);
  for (auto& t : arc_turns(1.0, 120.0, 0.5, 3))
    turns.push_back(t);
  const Ckt table = Ckt::build(turns);
  const TurnPrediction p = table.query(1.0, 90.0);
  ASSERT_TRUE(p.timing);
  EXPECT_NEAR(p.timing->length_m, arc_length_m(p.trajectory), 1e-9);
  const TurnPrediction lo = table.query(1.0, 60.0), hi = table.query(1.0, 120.0);
  EXPECT_GT(p.timing->time_s.back(), lo.timing->time_s.back());
  EXPECT_LT(p.timing->time_s.back(), hi.timing->time_s.back());
  const MaterializedCkt fine(table);
  const TurnPrediction f = fine.query(1.0, 90.5);
  ASSERT_TRUE(f.timing);
  EXPECT_NEAR(f.timing->length_m, arc_length_m(f.trajectory), 1e-9);
}

TEST(TurnTiming, KeptInTheCktFileAndAbsentFromOlderSchemas) {
  const Ckt table = Ckt::build(arc_turns(1.0, 90.0, 0.5, 3));
  const Ckt back = parse_ckt_json(ckt_to_json_string(table));
  ASSERT_TRUE(back.cell(0, 0).timing);
  for (std::size_t i = 0; i < kTimingStations; ++i)
    EXPECT_NEAR(back.cell(0, 0).timing->time_s[i], table.cell(0, 0).timing->time_s[i], 1e-9);
  nlohmann::json doc = ckt_to_json(table);
  doc.erase("frame");  // a field of schema 4
  doc["schema_version"] = 2;
  try {
    parse_ckt_json(doc.dump());
    FAIL() << "a timing in schema 2 must be refused";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/cells/0/timing"), std::string::npos) << e.what();
  }
  doc["cells"][0].erase("timing");
  EXPECT_FALSE(parse_ckt_json(doc.dump()).cell(0, 0).timing);
  doc["schema_version"] = 3;
  doc["cells"][0]["timing"] = {{"length_m", 5.0}, {"time_s", std::vector<double>(101, 1.0)}};
  try {
    parse_ckt_json(doc.dump());
    FAIL() << "a timing that does not start at 0 must be refused";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/cells/0/timing/time_s/0"), std::string::npos)
        << e.what();
  }
}

}  // namespace
