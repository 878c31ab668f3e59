// The .alog import use case: navigation stored as imported rows of a mission that ends done, bad
// lines counted and named, nothing stored for a request without a vehicle.
#include <gtest/gtest.h>

#include <sstream>

#include "app/alog_import.hpp"
#include "app/context.hpp"
#include "app/missions.hpp"
#include "app/store_access.hpp"
#include "mission/helm_mode.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

std::string small_log() {
  std::string log = "%% LOGFILE: test.alog\n";
  for (int k = 0; k < 40; ++k) {
    const std::string t = std::to_string(1.0 + 0.25 * k);
    log += t + " NAV_X uSimMarine " + std::to_string(0.5 * k) + "\n";
    log += t + " NAV_Y uSimMarine 3.0\n";
    log += t + " NAV_HEADING uSimMarine 90\n";
    log += t + " NAV_SPEED uSimMarine 2.0\n";
    if (k == 10) log += "this line is not a posting\n";
  }
  return log;
}

// The import of test.alog as the vehicle's.
app::AlogImportRequest request_for(const std::string& vehicle_id) {
  app::AlogImportRequest r;
  r.source = "test.alog";
  r.mission_name = "test.alog";
  r.vehicle_id = vehicle_id;
  return r;
}

TEST(AlogImport, StoresTheNavigationAsAFinishedMissionAndNamesBadLines) {
  avk::testing::TempDb db("avk_app_alog");
  app::Context ctx(db.path());
  std::istringstream in(small_log());
  const auto report = app::import_alog(ctx, in, request_for("kf"));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report->nav_stored, 40u);
  EXPECT_EQ(report->malformed.count, 1u);
  ASSERT_FALSE(report->malformed.first.empty());
  EXPECT_EQ(report->malformed.first[0].line, 46u);  // 1 header + 11 x 4 postings + 1
  EXPECT_EQ(report->from_records.total() + report->from_extraction.total(), 0);
  const auto m = app::mission_report(ctx, report->mission_id);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->summary.status, app::MissionStatus::done);
  EXPECT_TRUE(m->cells.empty());  // an imported log plans no turn array
  const auto nav = app::store_of(ctx).navigation().for_mission(report->mission_id);
  ASSERT_EQ(nav.size(), 40u);
  EXPECT_EQ(nav[0].helm_mode, mission::kImportedHelmMode);
  EXPECT_DOUBLE_EQ(nav.back().x_m, 19.5);
  // The top speed seen becomes the vehicle's.
  EXPECT_DOUBLE_EQ(app::store_of(ctx).vehicles().get("kf")->max_speed_mps, 2.0);
}

TEST(AlogImport, WithoutAVehicleNothingIsStored) {
  avk::testing::TempDb db("avk_app_alog");
  app::Context ctx(db.path());
  std::istringstream in(small_log());
  const auto report = app::import_alog(ctx, in, {});
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().field, "vehicle");
  EXPECT_TRUE(app::store_of(ctx).missions().list().empty());
}

// The vehicle id (--vehicle, else the file's stem) is bounded like every vehicle id.
TEST(AlogImport, AVehicleIdTooLongIsRefusedNamingTheLimit) {
  avk::testing::TempDb db("avk_app_alog");
  app::Context ctx(db.path());
  std::istringstream in(small_log());
  const auto r = request_for(std::string(65, 'v'));
  const auto report = app::import_alog(ctx, in, r);
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().field, "vehicle");
  EXPECT_NE(report.error().message.find("at most 64 bytes"), std::string::npos)
      << report.error().message;
  EXPECT_TRUE(app::store_of(ctx).missions().list().empty());
  EXPECT_FALSE(app::store_of(ctx).vehicles().get(r.vehicle_id));
}

}  // namespace
