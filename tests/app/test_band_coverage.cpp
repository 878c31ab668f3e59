// The position band's coverage on whole unseen missions: the run after a turn is scored only while
// the turn's own command holds (a new command at the turn's end, the next condition set or the
// containment turning back, is not the prediction's to answer), the table never holds a mission it
// is judged on, and in calm water a deterministic simulator's turns fall inside their band.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/band_coverage.hpp"
#include "app/context.hpp"
#include "app/current.hpp"
#include "app/mission_legs.hpp"
#include "app/store_access.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
namespace kin = avk::kinematics;

// The samples after each ok turn of the mission while the command of the turn's last sample
// holds, within after_s: counted from the navigation independently of band_coverage.
std::size_t after_turn_samples(store::Store& db, std::int64_t mission, double after_s) {
  const auto nav = db.navigation().for_mission(mission);
  std::size_t n = 0;
  std::vector<store::TurnRow> rows;
  app::for_each_mission_turn(db, mission, kin::TurnStatus::ok,
                             [&](const store::TurnRow& r) { rows.push_back(r); });
  for (const auto& row : rows) {
    const auto stored = db.turns().get(row.id);
    const double end = stored->raw.samples().back().t_s;
    const auto last = std::find_if(nav.rbegin(), nav.rend(),
                                   [&](const store::NavRow& r) { return r.t_s <= end; });
    if (last == nav.rend()) continue;
    for (const auto& r : nav) {
      if (r.t_s <= end) continue;
      if (r.t_s > end + after_s) break;
      if (r.desired_heading_deg != last->desired_heading_deg ||
          r.desired_speed_mps != last->desired_speed_mps)
        break;
      ++n;
    }
  }
  return n;
}

TEST(BandCoverage, TheRunAfterATurnEndsWithItsCommand) {
  avk::testing::TempDb db("avk_app_band_coverage");
  app::Context ctx(db.path());
  // A region just wide enough for the turns: the containment turns back as some turns end.
  constexpr const char* kTight = R"({
    "name": "tight",
    "turn_array": {"speeds_mps": [1.0, 1.5], "dheadings_deg": [40, 90], "repeats": 2},
    "operating_region": {"polygon_m": [[-45,-45],[45,-45],[45,45],[-45,45]],
                         "buffer_m": 10, "return_point_m": [0, -30]}})";
  std::vector<std::int64_t> missions;
  for (int k = 0; k < 3; ++k)
    missions.push_back(avk::testing::run_recorded_mission(app::store_of(ctx), "usim", kTight));

  app::BandCoverageQuery q;
  q.vehicle_id = "usim";
  q.test_missions = {missions[2]};
  // The test mission named among the table's is left out of it.
  q.table_missions = missions;
  const auto r = app::band_coverage(ctx, q);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->table_missions, (std::vector<std::int64_t>{missions[0], missions[1]}));
  EXPECT_GT(r->turns, 0u);
  EXPECT_EQ(r->after_turn.total,
            after_turn_samples(app::store_of(ctx), missions[2], q.after_turn_s));
  EXPECT_EQ(r->all.total, r->during_turn.total + r->after_turn.total);
  // Calm water, one simulator: the band holds nearly every point, and the run after the turn
  // stays close to the prediction (the next command's turn would take it metres away).
  EXPECT_GE(r->all.share(), 0.85);
  EXPECT_LT(r->errors_after_turn.cross_rms_m, 1.0);
  EXPECT_LT(r->errors_after_turn.along_rms_m, 1.0);
}

TEST(BandCoverage, BadQueriesNameTheField) {
  avk::testing::TempDb db("avk_app_band_coverage_bad");
  app::Context ctx(db.path());
  app::BandCoverageQuery q;
  q.vehicle_id = "usim";
  auto r = app::band_coverage(ctx, q);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "test_missions");
  q.test_missions = {7};
  q.share = 1.0;
  r = app::band_coverage(ctx, q);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "share");
  q.share = 0.9;
  r = app::band_coverage(ctx, q);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, app::ErrorCode::not_found);
}

}  // namespace
