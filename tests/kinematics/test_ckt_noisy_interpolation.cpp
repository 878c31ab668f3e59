// Interpolation in a table of noisy turns never rotates a turn: every answer, on a grid point or
// between them, ends on the heading it was asked for. The mean of noisy turns at low speed can
// start with a short segment pointing backwards; unwrapping the heading profile from it once
// carried a 360 deg wrap into the cell's profile, and its blends with neighbours that end on their
// goal came out rotated by up to 180 deg.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;
using avk::testing::ArcTurnSpec;
using avk::testing::make_arc_turn;

namespace {

// A turn of the synthetic vehicle (lead-in 0.5 + u m, radius 1 + 2u m) with GNSS-like position
// noise, whose fixes in the first second lag behind the start by up to lag_m, as a fix that
// catches up with the vehicle does: the recorded path starts by going backwards.
TurnSequence noisy_turn(double speed_mps, double dheading_deg, double noise_m, double lag_m,
                        unsigned seed) {
  ArcTurnSpec s;
  s.speed_mps = speed_mps;
  s.dheading_deg = dheading_deg;
  s.lead_in_m = 0.5 + speed_mps;
  s.radius_m = 1.0 + 2.0 * speed_mps;
  s.dt_s = 0.25;
  s.position_noise_m = noise_m;
  s.seed = seed;
  s.start = {-40.0 + 7.0 * (seed % 11), 25.0 - 5.0 * (seed % 9), 31.0 * seed};
  const TurnSequence clean = make_arc_turn(s);
  std::vector<TurnSample> samples = clean.samples();
  const double h = deg_to_rad(s.start.heading_deg);
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const double age_s = samples[k].t_s - samples[0].t_s;
    if (age_s >= 1.0) break;
    const double back_m = lag_m * (1.0 - age_s);
    samples[k].x_m -= back_m * std::sin(h);
    samples[k].y_m -= back_m * std::cos(h);
  }
  TurnSequence t(clean.meta(), std::move(samples));
  t.fill_derived_metadata();
  t.meta().initial_heading_deg = s.start.heading_deg;
  return t;
}

// Three turns a cell (alternating sides) at 0.5, 1.0, 1.5 m/s and 10..160 deg plus 180 deg.
Ckt noisy_table(double noise_m, double lag_m, unsigned seed) {
  std::vector<TurnSequence> turns;
  for (double u : {0.5, 1.0, 1.5}) {
    for (double d : {10.0, 40.0, 70.0, 100.0, 130.0, 160.0, 180.0}) {
      for (int r = 0; r < 3; ++r)
        turns.push_back(noisy_turn(u, r % 2 ? -d : d, noise_m, lag_m, seed++));
    }
  }
  return Ckt::build(turns);
}

double final_heading_deg(const Polyline& line) {
  const Point& a = line[line.size() - 2];
  const Point& b = line.back();
  return heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
}

constexpr double kToleranceDeg = 5.0;

}  // namespace

// Every (speed, heading change) on a 0.05 m/s x 5 deg grid (most of it between the table's cells,
// both sides), by the table and by the fine table guidance uses between its rows and columns.
TEST(CktNoisyInterpolation, EveryAnswerEndsOnItsGoalHeading) {
  struct Case {
    double noise_m, lag_m;
    unsigned seed;
  };
  for (const Case k : {Case{0.5, 0.6, 1}, Case{0.75, 0.4, 1000}, Case{1.0, 0.8, 3000}}) {
    const Ckt t = noisy_table(k.noise_m, k.lag_m, k.seed);
    const MaterializedCkt fine(t);
    std::size_t rotated = 0, queries = 0;
    std::ostringstream first;
    for (int i = 0; i <= 20; ++i) {
      const double u = 0.5 + 0.05 * i;
      for (int j = -36; j <= 36; ++j) {
        const double d = 5.0 * j;
        const double d_fine = d - (j > 0 ? 2.5 : j < 0 ? -2.5 : 0.0);  // between fine columns
        const double table_off =
            std::abs(angle180_deg(final_heading_deg(t.query(u, d).trajectory) - d));
        const double fine_off =
            std::abs(angle180_deg(final_heading_deg(fine.query(u, d_fine).trajectory) - d_fine));
        queries += 2;
        for (const auto& [off, asked] : {std::pair{table_off, d}, std::pair{fine_off, d_fine}}) {
          if (off <= kToleranceDeg) continue;
          if (rotated++ == 0) first << u << " m/s, " << asked << " deg: " << off << " deg off";
        }
      }
    }
    EXPECT_EQ(rotated, 0u) << "noise " << k.noise_m << " m, lag " << k.lag_m << " m: " << rotated
                           << " of " << queries << " answers off their goal, first " << first.str();
  }
}
