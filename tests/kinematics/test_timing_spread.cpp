// The along-track spread of a cell's turns: how far ahead or behind its mean a turn passes each
// point of the trajectory, computed turn by turn, blended and stretched like the times, and kept
// in the CKT file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt3.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_timing.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using namespace avk::kinematics;

// A lead-in, a 90 deg arc of radius 3 m and a straight tail, as a polyline of 0.5 m chords.
Polyline test_trajectory() {
  avk::testing::ArcTurnSpec spec;
  spec.lead_in_m = 2.0;
  spec.radius_m = 3.0;
  spec.dheading_deg = 90.0;
  spec.tail_m = 3.0;
  const double total = avk::testing::arc_turn_length_m(spec);
  Polyline out;
  for (double s = 0.0; s < total; s += 0.5)
    out.push_back(avk::testing::arc_turn_point(spec, s, nullptr));
  out.push_back(avk::testing::arc_turn_point(spec, total, nullptr));
  return out;
}

// The point at length g along the polyline; past its end along its last segment.
Point along(const Polyline& line, double g) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double d = distance_m(line[i], line[i + 1]);
    if (g <= s + d || i + 2 == line.size()) {
      const double u = (g - s) / d;
      return {line[i].x_m + u * (line[i + 1].x_m - line[i].x_m),
              line[i].y_m + u * (line[i + 1].y_m - line[i].y_m)};
    }
    s += d;
  }
  return line.back();
}

// A turn along the trajectory itself, stationed by time at the commanded speed: at rest for
// delay_steps samples of dt_s, then at speed_mps until it has gone end_m (past the trajectory's
// end along its last segment). The moment it reaches the trajectory's end is a sample, so its
// time there is exact. On the sample grid the distance is counted in whole steps, so delayed
// copies of a turn are at exactly the same points.
StationedPath along_trajectory(const Polyline& trajectory, double commanded_mps, double speed_mps,
                               int delay_steps, double end_m, double dt_s = 0.02) {
  const double length = arc_length_m(trajectory);
  const double delay = delay_steps * dt_s, t_end = delay + end_m / speed_mps;
  std::vector<std::pair<double, double>> samples;  // time, distance gone
  for (int j = 0; j * dt_s < t_end; ++j)
    samples.push_back({j * dt_s, std::max(0, j - delay_steps) * dt_s * speed_mps});
  if (length < end_m) samples.push_back({delay + length / speed_mps, length});
  samples.push_back({t_end, end_m});
  std::sort(samples.begin(), samples.end());
  StationedPath p;
  for (const auto& [t, g] : samples) {
    p.s_m.push_back(commanded_mps * t);
    p.points.push_back(along(trajectory, g));
  }
  return p;
}

double sample_sd(const std::vector<double>& v) {
  double mean = 0.0;
  for (const double x : v)
    mean += x / static_cast<double>(v.size());
  double ss = 0.0;
  for (const double x : v)
    ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

double station_length(double length_m, std::size_t i) {
  return length_m * static_cast<double>(i) / static_cast<double>(kTimingStations - 1);
}

TEST(TimingSpread, TurnsDelayedByConstantTimesSpreadByTheDelays) {
  const Polyline traj = test_trajectory();
  const double length = arc_length_m(traj);
  const std::vector<int> delay_steps{0, 25, 75, 100};  // 0, 0.5, 1.5, 2 s at 0.02 s
  std::vector<StationedPath> turns;
  std::vector<double> delays;
  for (const int d : delay_steps) {
    turns.push_back(along_trajectory(traj, 1.0, 1.0, d, length));
    delays.push_back(d * 0.02);
  }
  const std::vector<double> sd = timing_spread_s(turns, 1.0, traj);
  ASSERT_EQ(sd.size(), kTimingStations);
  EXPECT_EQ(sd[0], 0.0);  // every turn is at the start at the command
  for (std::size_t i = 1; i < kTimingStations; ++i)
    EXPECT_NEAR(sd[i], sample_sd(delays), 1e-9) << i;
}

// Turns along the trajectory at constant speeds other than the commanded one, each running
// run_on_m past its end, sampled every dt_s: a turn passes length l at l / v, so the spread is
// l times the sample sd of 1 / v at every station.
void expect_spread_in_proportion(const Polyline& traj, double commanded_mps,
                                 const std::vector<double>& speeds, double run_on_m, double dt_s) {
  const double length = arc_length_m(traj);
  std::vector<StationedPath> turns;
  std::vector<double> inverse;
  for (const double v : speeds) {
    turns.push_back(along_trajectory(traj, commanded_mps, v, 0, length + run_on_m, dt_s));
    inverse.push_back(1.0 / v);
  }
  const std::vector<double> sd = timing_spread_s(turns, commanded_mps, traj);
  ASSERT_EQ(sd.size(), kTimingStations);
  for (std::size_t i = 0; i < kTimingStations; ++i)
    EXPECT_NEAR(sd[i], station_length(length, i) * sample_sd(inverse), 1e-9) << i;
}

TEST(TimingSpread, TurnsAtDifferentSpeedsSpreadInProportionToLength) {
  // Commanded 1 m/s, flown at 0.8, 1 and 1.25 m/s. Each runs 2 m past the trajectory's end: it
  // reaches the end when it first gets there, not when it stops.
  expect_spread_in_proportion(test_trajectory(), 1.0, {0.8, 1.0, 1.25}, 2.0, 0.02);
}

TEST(TimingSpread, SparseFixesAreFollowedAlongAFinelyDividedTrajectory) {
  // Fixes 1.6-2.5 m apart (1 s at up to 2.5 m/s) on a straight trajectory of 0.1 m segments: far
  // more segments between fixes than the forward search looks ahead, so the turns are densified
  // first; along a straight line that is exact.
  Polyline traj;
  for (int k = 0; k <= 100; ++k)
    traj.push_back({0.0, 0.1 * k});
  expect_spread_in_proportion(traj, 2.0, {1.6, 2.0, 2.5}, 3.0, 1.0);
}

TEST(TimingSpread, ATurnThatEndsEarlyRunsOnAtTheCommandedSpeed) {
  // One turn at the commanded 1 m/s over the whole trajectory, one at 0.5 m/s that stops at half
  // of it and is carried on at 1 m/s: it is l behind up to the half, then half the length behind.
  const Polyline traj = test_trajectory();
  const double length = arc_length_m(traj);
  const std::vector<StationedPath> turns{along_trajectory(traj, 1.0, 1.0, 0, length),
                                         along_trajectory(traj, 1.0, 0.5, 0, length / 2.0)};
  const std::vector<double> sd = timing_spread_s(turns, 1.0, traj);
  ASSERT_EQ(sd.size(), kTimingStations);
  for (std::size_t i = 0; i < kTimingStations; ++i) {
    const double l = station_length(length, i);
    EXPECT_NEAR(sd[i], std::min(l, length / 2.0) / std::sqrt(2.0), 1e-9) << i;
  }
}

TEST(TimingSpread, IdenticalTurnsHaveNoSpreadAndOneTurnHasNone) {
  avk::testing::ArcTurnSpec s;
  s.dt_s = 0.5;  // sparse fixes, 0.5 m apart: densified before they are projected
  s.position_noise_m = 0.05;
  s.tail_m = 2.0;
  const StationedPath turn = stationed_by_time(avk::testing::make_arc_turn(s));
  const Polyline traj = test_trajectory();
  const std::vector<double> sd = timing_spread_s({turn, turn, turn}, 1.0, traj);
  ASSERT_EQ(sd.size(), kTimingStations);
  for (const double v : sd)
    EXPECT_NEAR(v, 0.0, 1e-12);
  EXPECT_TRUE(timing_spread_s({turn}, 1.0, traj).empty());
  EXPECT_TRUE(timing_spread_s({turn, turn}, 0.0, traj).empty());
  EXPECT_TRUE(timing_spread_s({turn, turn}, 1.0, {{0.0, 0.0}}).empty());
}

TEST(TimingSpread, UnchangedByMovingAndRotatingEverything) {
  std::vector<StationedPath> turns;
  for (const double v : {0.7, 0.9, 1.1, 1.3}) {
    avk::testing::ArcTurnSpec s;
    s.speed_mps = v;
    s.dt_s = 0.1;
    s.tail_m = 2.0;
    s.position_noise_m = 0.03;
    s.seed = static_cast<unsigned>(v * 10.0);
    avk::kinematics::TurnSequence t = avk::testing::make_arc_turn(s);
    t.meta().commanded_speed_mps = 1.0;
    turns.push_back(stationed_by_time(t));
  }
  const Polyline traj = test_trajectory();
  const std::vector<double> sd = timing_spread_s(turns, 1.0, traj);
  ASSERT_EQ(sd.size(), kTimingStations);
  EXPECT_GT(sd[50], 0.1);
  const double a = deg_to_rad(37.0), c = std::cos(a), s = std::sin(a);
  const auto moved = [&](Point p) {
    return Point{c * p.x_m - s * p.y_m + 120.0, s * p.x_m + c * p.y_m - 45.0};
  };
  std::vector<StationedPath> moved_turns = turns;
  for (auto& t : moved_turns)
    for (auto& p : t.points)
      p = moved(p);
  Polyline moved_traj = traj;
  for (auto& p : moved_traj)
    p = moved(p);
  const std::vector<double> moved_sd = timing_spread_s(moved_turns, 1.0, moved_traj);
  ASSERT_EQ(moved_sd.size(), kTimingStations);
  for (std::size_t i = 0; i < kTimingStations; ++i)
    EXPECT_NEAR(moved_sd[i], sd[i], 1e-9) << i;
}

TurnTiming spread_timing(double length_m, double speed_mps, double sd_per_m) {
  TurnTiming t = constant_speed_timing(length_m, speed_mps);
  for (std::size_t i = 0; i < kTimingStations; ++i)
    t.time_sd_s.push_back(sd_per_m * station_length(length_m, i));
  return t;
}

TEST(TimingSpread, BlendedAndStretchedLikeTheTimes) {
  const std::optional<TurnTiming> a = spread_timing(10.0, 1.0, 0.1),
                                  b = spread_timing(20.0, 0.5, 0.3);
  const auto m = blend_timings({{&a, 0.25}, {&b, 0.75}});
  ASSERT_TRUE(m);
  ASSERT_EQ(m->time_sd_s.size(), kTimingStations);
  EXPECT_NEAR(m->time_sd_s.back(), 0.25 * 1.0 + 0.75 * 6.0, 1e-12);
  EXPECT_NEAR(m->time_sd_s[50], 0.25 * 0.5 + 0.75 * 3.0, 1e-12);
  // A source without spread: the times still blend, the spread is not known.
  std::optional<TurnTiming> bare = b;
  bare->time_sd_s.clear();
  const auto n = blend_timings({{&a, 0.5}, {&bare, 0.5}});
  ASSERT_TRUE(n);
  EXPECT_TRUE(n->time_sd_s.empty());
  EXPECT_EQ(time_sd_at_length_s(*n, 5.0), 0.0);
  // Stretched to 1.5 times the length at the same mean speed: the spread grows with the times.
  const TurnTiming s = scaled_timing(*a, 15.0);
  EXPECT_NEAR(s.time_sd_s.back(), 1.5, 1e-12);
  EXPECT_NEAR(time_sd_at_length_s(s, 7.5), 0.75, 1e-12);
  EXPECT_NEAR(time_sd_at_length_s(*a, 2.55), 0.255, 1e-12);  // between stations
  EXPECT_NEAR(time_sd_at_length_s(*a, 40.0), 1.0, 1e-12);    // past the end: the last value
  EXPECT_EQ(time_sd_at_length_s(*a, 0.0), 0.0);
}

std::vector<TurnSequence> turns_at_speeds(double commanded_mps, double dheading_deg,
                                          const std::vector<double>& speeds) {
  std::vector<TurnSequence> out;
  unsigned seed = 1;
  for (const double v : speeds) {
    avk::testing::ArcTurnSpec s;
    s.speed_mps = v;
    s.dheading_deg = dheading_deg;
    s.lead_in_m = 1.0;
    s.radius_m = 3.0;
    s.dt_s = 0.1;
    s.tail_m = 2.0;
    s.seed = seed++;
    s.position_noise_m = 0.02;
    TurnSequence t = avk::testing::make_arc_turn(s);
    t.meta().commanded_speed_mps = commanded_mps;
    out.push_back(t);
  }
  return out;
}

TEST(TimingSpread, TheTableRecordsItPerCellAndCarriesItToQueries) {
  std::vector<TurnSequence> turns = turns_at_speeds(1.0, 60.0, {0.8, 1.0, 1.25});
  for (auto& t : turns_at_speeds(1.0, 120.0, {0.8, 1.0, 1.25}))
    turns.push_back(t);
  const Ckt table = Ckt::build(turns);
  const CktCell& c = table.cell(0, 0);
  ASSERT_TRUE(c.timing);
  ASSERT_EQ(c.timing->time_sd_s.size(), kTimingStations);
  // 3 m along: l / v for v = 0.8, 1, 1.25, within the noise and the trajectory's fit.
  const double expected = 3.0 * sample_sd({1.0 / 0.8, 1.0, 1.0 / 1.25});
  EXPECT_NEAR(time_sd_at_length_s(*c.timing, 3.0), expected, 0.15 * expected);
  const TurnPrediction p = table.query(1.0, 90.0);
  ASSERT_TRUE(p.timing);
  ASSERT_EQ(p.timing->time_sd_s.size(), kTimingStations);
  EXPECT_GT(p.timing->time_sd_s[50], 0.0);
  const MaterializedCkt fine(table);
  const TurnPrediction f = fine.query(1.0, 90.5);
  ASSERT_TRUE(f.timing);
  EXPECT_EQ(f.timing->time_sd_s.size(), kTimingStations);
  // Between two yaw-rate slices, as between cells.
  const YawRateCkt rated = YawRateCkt::from_slices(
      {{0.0, table, std::vector<CellSource>(table.cells().size(), CellSource::measured)},
       {10.0, table, std::vector<CellSource>(table.cells().size(), CellSource::measured)}});
  const YawRatePrediction r = rated.query(1.0, 60.0, 5.0);
  ASSERT_TRUE(r.prediction.timing);
  ASSERT_EQ(r.prediction.timing->time_sd_s.size(), kTimingStations);
  EXPECT_NEAR(r.prediction.timing->time_sd_s.back(), c.timing->time_sd_s.back(),
              0.02 * c.timing->time_sd_s.back());
}

TEST(TimingSpread, KeptInTheCktFileAndOptionalOnRead) {
  const Ckt table = Ckt::build(turns_at_speeds(1.0, 90.0, {0.8, 1.0, 1.25}));
  ASSERT_TRUE(table.cell(0, 0).timing);
  ASSERT_FALSE(table.cell(0, 0).timing->time_sd_s.empty());
  const Ckt back = parse_ckt_json(ckt_to_json_string(table));
  ASSERT_TRUE(back.cell(0, 0).timing);
  EXPECT_EQ(back.cell(0, 0).timing->time_sd_s, table.cell(0, 0).timing->time_sd_s);
  // A file written before the spread was recorded still loads, without it.
  nlohmann::json doc = ckt_to_json(table);
  doc["cells"][0]["timing"].erase("time_sd_s");
  const Ckt old = parse_ckt_json(doc.dump());
  ASSERT_TRUE(old.cell(0, 0).timing);
  EXPECT_TRUE(old.cell(0, 0).timing->time_sd_s.empty());
  EXPECT_EQ(old.cell(0, 0).timing->time_s, table.cell(0, 0).timing->time_s);
  const auto refused = [&](const nlohmann::json& sd, const std::string& where) {
    nlohmann::json bad = ckt_to_json(table);
    bad["cells"][0]["timing"]["time_sd_s"] = sd;
    try {
      parse_ckt_json(bad.dump());
      ADD_FAILURE() << "refused at " << where;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  };
  refused(std::vector<double>(100, 0.1), "/cells/0/timing/time_sd_s");
  std::vector<double> negative(kTimingStations, 0.1);
  negative[7] = -0.1;
  refused(negative, "/cells/0/timing/time_sd_s/7");
  refused("fast", "/cells/0/timing/time_sd_s");
}

}  // namespace
