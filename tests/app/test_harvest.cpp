// Harvesting turns from simulated missions: the Figure 4-1 collection mission
// on the calibrated M200 (its harvested turns are its collected turns, sample for sample, when
// the collected ones are not skipped) and a persistent-excitation mission (thesis §3.4.2), whose
// heading steps every 3-10 s mostly come while the vehicle is still swinging.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/harvest.hpp"
#include "app/store_access.hpp"
#include "app/store_views.hpp"
#include "kinematics/angles.hpp"
#include "mission/turn_harvester.hpp"
#include "support/example_file.hpp"
#include "support/guided_boat.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

void print(const char* what, const app::HarvestReport& r) {
  std::printf(
      "%s: %zu steps, %zu harvested (mean quality %.2f), %zu already recorded, %zu "
      "rejected:",
      what, r.steps, r.harvested, r.mean_quality, r.already_recorded, r.rejected);
  for (const auto& [reason, n] : r.rejected_by_reason)
    if (n) std::printf(" %s %zu", reason.c_str(), n);
  std::printf("\n");
}

TEST(Harvest, TheFigure41MissionsHarvestedTurnsAreItsCollectedTurns) {
  avk::testing::TempDb db("avk_app_harvest_fig41");
  app::Context ctx(db.path());
  const std::int64_t mission = avk::testing::run_recorded_mission(
      app::store_of(ctx), "m200", avk::testing::example_text("thesis-fig4-1.json"),
      sim::default_sim_setup("catamaran:m200"));
  store::Store& s = app::store_of(ctx);
  store::TurnFilter f;
  f.mission_id = mission;
  f.status = kinematics::TurnStatus::ok;
  f.limit = 1000;
  const auto collected = s.turns().list(f);
  ASSERT_GE(collected.size(), 15u);

  // Not skipping the collected turns: the harvester finds each of them again.
  const auto config =
      mission::parse_mission_config(avk::testing::example_text("thesis-fig4-1.json"), 2.0);
  mission::HarvestOptions options;
  options.extraction.condition_set = config.condition_set;
  options.extraction.completion = config.completion;
  const auto log = app::guided_log(s.navigation().for_mission(mission));
  const auto fresh = mission::harvest_turns(log, {}, options, "m200", std::to_string(mission));
  std::size_t matched = 0;
  for (const auto& row : collected) {
    const auto stored = s.turns().get(row.id);
    ASSERT_TRUE(stored);
    for (const auto& h : fresh.turns) {
      if (std::abs(h.turn.meta().start_time_s - row.start_time_s) > 1e-6) continue;
      ++matched;
      const auto& a = h.turn.samples();
      const auto& b = stored->raw.samples();
      ASSERT_EQ(a.size(), b.size()) << "turn " << row.id;
      for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i].x_m, b[i].x_m, 1e-6);
        EXPECT_NEAR(a[i].y_m, b[i].y_m, 1e-6);
        EXPECT_NEAR(kinematics::angle180_deg(a[i].heading_deg - b[i].heading_deg), 0.0, 1e-6);
      }
      EXPECT_NEAR(h.turn.meta().goal_dheading_deg, row.goal_dheading_deg, 1.0);
      EXPECT_GT(*h.turn.meta().quality, 0.0);
      EXPECT_LE(*h.turn.meta().quality, 1.0);
    }
  }
  EXPECT_EQ(matched, collected.size());

  // Harvesting the stored mission skips them: nothing is counted twice.
  const auto r = app::harvest_mission(ctx, mission);
  ASSERT_TRUE(r) << r.error().message;
  print("Figure 4-1 on the M200", *r);
  EXPECT_GE(r->already_recorded, collected.size());
  EXPECT_EQ(r->steps, r->harvested + r->already_recorded + r->rejected);
  EXPECT_EQ(app::store_of(ctx).harvests().list(mission).size(), 1u);
  // A second harvest finds its own turns recorded.
  const auto again = app::harvest_mission(ctx, mission);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->harvested, 0u);
  EXPECT_EQ(again->already_recorded, r->already_recorded + r->harvested);
}

TEST(Harvest, ExcitationStepsMidSwingAreRejectedAndTheSteadyOnesHarvested) {
  avk::testing::TempDb db("avk_app_harvest_excitation");
  app::Context ctx(db.path());
  std::string text = avk::testing::example_text("persistent-excitation.json");
  const auto at = text.find("\"duration_s\": 900");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "\"duration_s\": 300");  // a third of it: the test stays short
  const std::int64_t mission = avk::testing::run_recorded_mission(
      app::store_of(ctx), "m200", text, sim::default_sim_setup("catamaran:m200"));
  const auto r = app::harvest_mission(ctx, mission);
  ASSERT_TRUE(r) << r.error().message;
  print("persistent excitation (300 s) on the M200", *r);
  EXPECT_EQ(r->already_recorded, 0u);  // an excitation mission records no turns
  EXPECT_GE(r->steps, 30u);            // a step every 3-10 s
  // Steps 3-10 s apart against turns of several seconds: most start mid-swing or are
  // interrupted by the next one.
  const auto& by = r->rejected_by_reason;
  EXPECT_GT(by.at("not_steady_before") + by.at("goal_changed_during_turn"), r->steps / 2);
  EXPECT_EQ(r->steps, r->harvested + r->rejected);

  // Ground truth for the accepted ones: the recorded heading was steady over the 2 s before
  // each harvested turn (not mid-swing), and the turn reached its goal.
  const auto nav = app::store_of(ctx).navigation().for_mission(mission);
  for (const auto id : r->turn_ids) {
    const auto t = app::store_of(ctx).turns().get(id);
    ASSERT_TRUE(t);
    const double t0 = t->raw.meta().start_time_s;
    for (const auto& n : nav) {
      if (n.t_s < t0 - 2.0 || n.t_s > t0) continue;
      EXPECT_LT(std::abs(kinematics::angle180_deg(n.heading_deg - t->raw.samples()[0].heading_deg)),
                3.0)
          << "turn " << id << " at " << n.t_s;
    }
    EXPECT_EQ(t->row.source, kinematics::TurnSource::harvested);
    EXPECT_NEAR(
        std::abs(t->raw.heading_change_deg()), std::abs(t->row.goal_dheading_deg),
        completion_threshold_deg(mission::CompletionRule{}, t->row.goal_dheading_deg) + 1.0);
  }

  // The table: none from collection turns alone, the harvested turns when asked for.
  if (r->harvested > 0) {
    EXPECT_FALSE(app::vehicle_table(ctx, "m200"));
    const auto both = app::vehicle_table(ctx, "m200", true);
    ASSERT_TRUE(both) << both.error().message;
    EXPECT_TRUE(both->include_harvested);
    const auto built = app::build_ckt(ctx, "m200", {}, {}, std::nullopt, true);
    ASSERT_TRUE(built);
    EXPECT_EQ(built->harvested_turns, r->harvested);
    EXPECT_FALSE(app::build_ckt(ctx, "m200", {}, {}));
  }
}

// A log with known steady steps, stored as a mission without turns: its turns are harvested,
// and only the table asked to include them uses them.
TEST(Harvest, HarvestedTurnsEnterTheTableOnlyWhenAskedFor) {
  avk::testing::TempDb db("avk_app_harvest_table");
  app::Context ctx(db.path());
  store::Store& s = app::store_of(ctx);
  s.vehicles().upsert({"boat", "usim", 2.0, 1.0});
  const auto mission = s.missions().create("boat", "log", "{}");
  avk::testing::Boat boat(0.0, 1.0);
  std::vector<store::NavRow> rows;
  double desired = 0.0;
  for (int step = 0; step < 4; ++step) {
    for (int i = 0; i < 60; ++i) {
      const auto g = boat.step(desired, 1.0, 10.0);
      rows.push_back({g.nav.t_s, g.nav.x_m, g.nav.y_m, g.nav.heading_deg, g.nav.speed_mps,
                      g.desired_heading_deg, g.desired_speed_mps, "IMPORTED"});
    }
    desired = kinematics::wrap360_deg(desired + 90.0);
  }
  s.navigation().append(mission, rows);
  const auto r = app::harvest_mission(ctx, mission);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->steps, 3u);
  EXPECT_EQ(r->harvested, 3u);
  EXPECT_FALSE(app::vehicle_table(ctx, "boat"));  // no collection turns: no table
  const auto table = app::vehicle_table(ctx, "boat", true);
  ASSERT_TRUE(table) << table.error().message;
  EXPECT_TRUE(table->include_harvested);
  EXPECT_FALSE(app::build_ckt(ctx, "boat", {}, {}));
  const auto built = app::build_ckt(ctx, "boat", {}, {}, std::nullopt, true);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->harvested_turns, 3u);
  EXPECT_EQ(built->report.turns_used, 3u);
  EXPECT_FALSE(app::harvest_mission(ctx, mission + 1));
}

}  // namespace
