// Missions through the use cases: validation with every problem, a mission run on the simulator
// (its own scheduler, no wall clock) reported, listed and paged, and the commands that cannot
// apply without the station's vehicle. Without HTTP or argv.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "app/context.hpp"
#include "app/mission_run.hpp"
#include "app/missions.hpp"
#include "app/store_access.hpp"
#include "app/turns.hpp"
#include "app/vehicles.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

constexpr const char* kMission = avk::testing::kSmallMission;

class Missions : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    db_ = new avk::testing::TempDb("avk_app_missions");
    store::Store db(db_->path());
    mission_ = avk::testing::run_recorded_mission(db, "sim-a");
    other_ = avk::testing::run_recorded_mission(db, "sim-b");
  }
  static void TearDownTestSuite() { delete db_; }
  static avk::testing::TempDb* db_;
  static std::int64_t mission_, other_;
  app::Context ctx_{db_->path()};
};
avk::testing::TempDb* Missions::db_ = nullptr;
std::int64_t Missions::mission_ = 0;
std::int64_t Missions::other_ = 0;

TEST(MissionValidation, EveryProblemIsListedWithItsField) {
  const auto r = app::validate_mission(
      R"({"name": "", "turn_array": {"speeds_mps": [9.0], "dheadings_deg": [400]}})", 2.0);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, app::ErrorCode::invalid_argument);
  std::set<std::string> fields;
  for (const auto& f : r.error().fields)
    fields.insert(f.field);
  EXPECT_GE(fields.size(), 3u);
  EXPECT_TRUE(fields.count("/operating_region")) << r.error().fields.front().field;
  const auto ok = app::validate_mission(kMission, 2.0);
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->name, "small");
}

TEST_F(Missions, TheReportMergesThePlanWithWhatIsStored) {
  const auto r = app::mission_report(ctx_, mission_);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_FALSE(r->live);
  EXPECT_EQ(r->summary.status, app::MissionStatus::done);
  EXPECT_EQ(app::status_text(*r), "done");
  ASSERT_EQ(r->cells.size(), 4u);  // 2 speeds x 2 heading changes
  std::int64_t ok = 0, aborted = 0, rejected = 0;
  for (const auto& c : r->cells) {
    EXPECT_EQ(c.planned, 2);
    ok += c.ok;
    aborted += c.aborted;
    rejected += c.rejected;
    if (c.ok) {
      ASSERT_TRUE(c.advance_m && c.transfer_m);
      EXPECT_GT(c.advance_m->mean, 0.0);
    }
  }
  EXPECT_EQ(ok, r->summary.turns.ok);
  EXPECT_EQ(aborted, r->summary.turns.aborted);
  EXPECT_EQ(rejected, r->summary.turns.rejected);
  EXPECT_EQ(r->summary.turns.ok, 8);
  ASSERT_TRUE(r->condition_set_time_s);
  EXPECT_GT(r->condition_set_time_s->mean, 0.0);
  EXPECT_EQ(r->condition_set_episodes.at("set"), static_cast<int>(r->condition_set_count));
  ASSERT_TRUE(r->duration_s);
  EXPECT_GT(*r->duration_s, 0.0);
  // Every turn, with how steady it began: no ok turn started off the held course or swinging.
  ASSERT_EQ(static_cast<std::int64_t>(r->turns.size()), r->summary.turns.total());
  for (const auto& t : r->turns) {
    EXPECT_EQ(t.mission_id, mission_);
    if (t.status != kinematics::TurnStatus::ok) continue;
    ASSERT_TRUE(t.start_heading_error_deg && t.start_yaw_rate_dps) << "turn " << t.id;
    EXPECT_LE(std::abs(*t.start_heading_error_deg), 2.0);
    EXPECT_LE(std::abs(*t.start_yaw_rate_dps), 1.0);
  }
  EXPECT_EQ(app::mission_report(ctx_, 9999).error().code, app::ErrorCode::not_found);
}

TEST_F(Missions, ListingFiltersByVehicle) {
  EXPECT_EQ(app::list_missions(ctx_, std::nullopt).size(), 2u);
  const auto a = app::list_missions(ctx_, std::string("sim-a"));
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].mission.id, mission_);
  EXPECT_EQ(a[0].turns.ok, 8);
  EXPECT_TRUE(app::list_missions(ctx_, std::string("nobody")).empty());
  const auto vehicles = app::list_vehicles(ctx_);
  ASSERT_EQ(vehicles.size(), 2u);
  EXPECT_FALSE(vehicles[0].live);  // no vehicle loop: both known from the store only
  EXPECT_EQ(app::get_vehicle(ctx_, "sim-b")->info.kind, "usim");
  EXPECT_EQ(app::get_vehicle(ctx_, "nobody").error().code, app::ErrorCode::not_found);
}

TEST_F(Missions, TrackAndEventPagesNeitherSkipNorRepeat) {
  const auto all = app::store_of(ctx_).navigation().for_mission(mission_);
  ASSERT_GT(all.size(), 100u);
  std::size_t seen = 0;
  std::int64_t after = 0;
  double last_t = -1e300;
  for (int pages = 0;; ++pages) {
    ASSERT_LT(pages, 1000);
    const auto page = app::mission_track(ctx_, mission_, after, 97);
    ASSERT_TRUE(page);
    for (const auto& row : page->items) {
      EXPECT_GE(row.t_s, last_t);
      last_t = row.t_s;
    }
    seen += page->items.size();
    if (!page->next) break;
    after = *page->next;
  }
  EXPECT_EQ(seen, all.size());
  const auto events = app::store_of(ctx_).missions().events(mission_);
  const auto first = app::mission_events(ctx_, mission_, 0, 1);
  ASSERT_TRUE(first);
  ASSERT_EQ(first->items.size(), 1u);
  ASSERT_TRUE(first->next);
  const auto rest = app::mission_events(ctx_, mission_, *first->next, 1000);
  EXPECT_EQ(1 + rest->items.size(), events.size());
  EXPECT_EQ(app::mission_track(ctx_, mission_, 0, 0).error().field, "limit");
  EXPECT_EQ(app::mission_events(ctx_, 9999, 0, 10).error().code, app::ErrorCode::not_found);
}

TEST_F(Missions, TheLastPositionIsTheLatestStoredReport) {
  const auto nav = app::store_of(ctx_).navigation().for_mission(mission_);
  ASSERT_FALSE(nav.empty());
  const auto last = app::mission_last_position(ctx_, mission_);
  ASSERT_TRUE(last) << last.error().message;
  // for_mission is in time order: its last row is the latest.
  EXPECT_EQ(last->t_s, nav.back().t_s);
  EXPECT_EQ(last->x_m, nav.back().x_m);
  EXPECT_EQ(last->y_m, nav.back().y_m);
  EXPECT_EQ(last->heading_deg, nav.back().heading_deg);
  EXPECT_EQ(last->helm_mode, nav.back().helm_mode);
  EXPECT_EQ(app::mission_last_position(ctx_, 9999).error().code, app::ErrorCode::not_found);
  // A mission that recorded nothing, in a database of its own (the suite's is shared).
  avk::testing::TempDb path{"avk_last_position"};
  app::Context fresh(path.path());
  app::store_of(fresh).vehicles().upsert({"sim-a", "usim", 2.0, std::nullopt});
  const auto empty = app::store_of(fresh).missions().create("sim-a", "empty", "{}");
  const auto none = app::mission_last_position(fresh, empty);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, app::ErrorCode::not_found);
  EXPECT_NE(none.error().message.find("recorded no navigation"), std::string::npos);
}

TEST_F(Missions, TurnPagesCoverEveryStoredTurnOnce) {
  app::TurnQuery f;
  f.mission_id = mission_;
  f.limit = 3;
  std::set<std::int64_t> ids;
  for (int pages = 0;; ++pages) {
    ASSERT_LT(pages, 100);
    const auto page = app::query_turns(ctx_, f);
    ASSERT_TRUE(page);
    for (const auto& t : page->items) {
      EXPECT_EQ(t.mission_id, mission_);
      EXPECT_TRUE(ids.insert(t.id).second) << t.id;
    }
    if (!page->next) break;
    f.after_id = *page->next;
  }
  store::TurnFilter all;
  all.mission_id = mission_;
  all.limit = 1000;
  EXPECT_EQ(ids.size(), app::store_of(ctx_).turns().list(all).size());
  const auto one = app::get_turn(ctx_, *ids.begin());
  ASSERT_TRUE(one);
  EXPECT_TRUE(one->normalized || one->row.status != kinematics::TurnStatus::ok);
  EXPECT_EQ(app::get_turn(ctx_, 999999).error().code, app::ErrorCode::not_found);
}

TEST_F(Missions, WithoutTheStationsVehicleNothingStartsOrResumes) {
  const auto start = app::start_mission(ctx_, "sim-a", kMission);
  ASSERT_FALSE(start);
  EXPECT_EQ(start.error().code, app::ErrorCode::conflict);
  const auto before = app::list_missions(ctx_, std::nullopt).size();
  // A finished mission is not running: pause and abort are conflicts, as is a resume here.
  for (const auto c :
       {app::MissionCommand::pause, app::MissionCommand::abort, app::MissionCommand::resume})
    EXPECT_EQ(app::command_mission(ctx_, mission_, c).error().code, app::ErrorCode::conflict)
        << app::to_string(c);
  EXPECT_EQ(app::command_mission(ctx_, 9999, app::MissionCommand::pause).error().code,
            app::ErrorCode::not_found);
  EXPECT_EQ(app::list_missions(ctx_, std::nullopt).size(), before);  // nothing was stored
}

TEST(CellReports, CarryTheRunnersCounts) {
  mission::CellProgress p;
  p.speed_mps = 1.0;
  p.dheading_deg = 40.0;
  p.planned = 3;
  p.ok = 2;
  p.rejected = 1;
  p.given_up = 1;
  p.running = true;
  const auto cells = app::cell_reports({p});
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].planned, 3);
  EXPECT_EQ(cells[0].ok, 2);
  EXPECT_EQ(cells[0].rejected, 1);
  EXPECT_EQ(cells[0].given_up, 1);
  EXPECT_TRUE(cells[0].running);
  EXPECT_FALSE(cells[0].advance_m);
}

}  // namespace

namespace {

using namespace avk;

app::VehicleSourceOptions simulated_usim(const std::string& id) {
  app::VehicleSourceOptions v;
  v.setup = sim::default_sim_setup("usim");
  v.setup.vehicle.id = id;
  v.realtime = false;
  return v;
}

TEST(MissionRunHere, RunsThePlanToItsEndAndRecordsIt) {
  avk::testing::TempDb db("avk_app_run");
  app::Context ctx(db.path());
  const auto r =
      app::run_new_mission(ctx, avk::testing::kSmallMission, simulated_usim("sim-here"), {});
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_FALSE(r->stopped);
  EXPECT_TRUE(r->simulated);
  EXPECT_EQ(r->planned, 8);
  EXPECT_EQ(r->summary.mission.vehicle_id, "sim-here");
  EXPECT_EQ(r->summary.status, app::MissionStatus::done);
  EXPECT_EQ(r->summary.turns.ok, 8);
  EXPECT_GT(r->end_time_s, r->start_time_s);
  EXPECT_FALSE(app::store_of(ctx)
                   .missions()
                   .get(r->summary.mission.id)
                   ->runner_pid);  // no longer running here
}

TEST(MissionRunHere, ARaisedStopFlagInterruptsItResumably) {
  avk::testing::TempDb db("avk_app_run");
  app::Context ctx(db.path());
  const std::atomic<bool> stop{true};
  app::MissionRunOptions o;
  o.stop = &stop;
  const auto r =
      app::run_new_mission(ctx, avk::testing::kSmallMission, simulated_usim("sim-here"), o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  EXPECT_EQ(r->summary.status, app::MissionStatus::interrupted);
  const auto resumed = app::resume_mission_plan(ctx, r->summary.mission.id, 2.0);
  ASSERT_TRUE(resumed) << resumed.error().message;
  EXPECT_EQ(resumed->tasks.size(), 8u);
}

}  // namespace
