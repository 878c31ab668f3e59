// `avk import alog` end to end: a simulated mission is written out as the .alog a MOOS vehicle
// would have logged (asynchronous postings from several processes, header, junk), imported, and
// the imported turns compared with the ones the mission itself recorded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "kinematics/turn_text.hpp"
#include "server/cli/cli.hpp"
#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/temp_db.hpp"

namespace fs = std::filesystem;
using avk::kinematics::TurnStatus;
using avk::store::Store;
using avk::testing::TempDb;

namespace {

using avk::testing::example;
using avk::testing::run;
using Result = avk::testing::CliResult;

// A file under the temp directory, removed before and after use.
class TempFile {
 public:
  explicit TempFile(const std::string& name) {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            (std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + name);
    fs::remove(path_);
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// Shortest round-trip form, as pLogger would write a double it was given exactly.
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<avk::store::StoredTurn> turns_of(Store& s, std::int64_t mission_id) {
  avk::store::TurnFilter f;
  f.mission_id = mission_id;
  f.limit = 100000;
  std::vector<avk::store::StoredTurn> out;
  for (const auto& row : s.turns().list(f))
    out.push_back(*s.turns().get(row.id));
  return out;
}

std::size_t count(const std::vector<avk::store::StoredTurn>& turns, TurnStatus status) {
  return static_cast<std::size_t>(std::count_if(
      turns.begin(), turns.end(), [&](const auto& t) { return t.row.status == status; }));
}

// The mission's navigation as pLogger logs it: uSimMarine's NAV_* of one report share a stamp,
// pHelmIvP posts DESIRED_* when it changes them, other processes post what they like, and a
// log collects some junk. Returns the line numbers of the junk lines.
struct AlogWriter {
  std::ofstream out;
  std::size_t line = 0;
  std::vector<std::size_t> junk;

  explicit AlogWriter(const std::string& path) : out(path, std::ios::binary) {
    put("%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%");
    put("%% LOGFILE:       /home/moos/logs/M200_12_6_2013/M200_12_6_2013.alog");
    put("%% FILE OPENED ON Wed Jun 12 10:21:07 2013");
    put("%% LOGSTART               1371046867.51");
    put("%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%%");
    put("");
  }
  void put(const std::string& s) {
    out << s << '\n';
    ++line;
  }
  void post(double t, const std::string& var, const std::string& src, const std::string& value) {
    std::string pad(std::max<std::size_t>(1, 20 - var.size()), ' ');
    put(num(t) + "   " + var + pad + src + "    " + value);
  }
  void bad(const std::string& s) {
    put(s);
    junk.push_back(line);
  }

  void nav_log(const std::vector<avk::store::NavRow>& nav) {
    std::optional<double> dh, ds;
    for (std::size_t i = 0; i < nav.size(); ++i) {
      const auto& r = nav[i];
      post(r.t_s, "NAV_X", "uSimMarine", num(r.x_m));
      post(r.t_s, "NAV_Y", "uSimMarine", num(r.y_m));
      if (i % 3 == 0) post(r.t_s, "NAV_LAT", "uSimMarine", "42.358456");
      post(r.t_s, "NAV_HEADING", "uSimMarine", num(r.heading_deg));
      post(r.t_s, "NAV_SPEED", "uSimMarine", num(r.speed_mps));
      if (r.desired_heading_deg && r.desired_heading_deg != dh) {
        dh = r.desired_heading_deg;
        post(r.t_s, "DESIRED_HEADING", "pHelmIvP", num(*dh));
      }
      if (r.desired_speed_mps && r.desired_speed_mps != ds) {
        ds = r.desired_speed_mps;
        post(r.t_s, "DESIRED_SPEED", "pHelmIvP", num(*ds));
      }
      if (i % 40 == 7) {
        post(r.t_s + 0.05, "IVPHELM_SUMMARY", "pHelmIvP",
             "iter=" + std::to_string(i) + ",ofnum=1,warnings=0,time=0.01, solve_time=0.00");
        post(r.t_s + 0.05, "DB_UPTIME", "MOOSDB_m200", num(r.t_s + 12.5));
      }
      if (i == 100) bad("this line is not a posting");
      if (i == 500) bad(num(r.t_s + 0.01) + " NAV_X");
      if (i == 900) bad("nan NAV_Y uSimMarine 12");
      if (i == 1300) bad(num(r.t_s + 0.01) + " NAV_HEADING uSimMarine north-east");
    }
  }
};

class ImportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const Result r = run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db",
                          mission_db_.path(), "--sim", "--quiet"});
    ASSERT_EQ(r.rc, 0) << r.out << r.err;
    Store s(mission_db_.path());
    nav_ = s.navigation().for_mission(1);
    turns_ = turns_of(s, 1);
    ASSERT_GT(nav_.size(), 1400u);
    ASSERT_EQ(count(turns_, TurnStatus::ok), 18u);
  }

  TempDb mission_db_{"avk_import_mission"};
  TempDb import_db_{"avk_import"};
  std::vector<avk::store::NavRow> nav_;
  std::vector<avk::store::StoredTurn> turns_;
};

TEST_F(ImportCli, ExtractsTheTurnsTheMissionRecordedFromItsNavigationLog) {
  TempFile alog("m200_2013.alog");
  std::vector<std::size_t> junk;
  {
    AlogWriter w(alog.path());
    w.nav_log(nav_);
    junk = w.junk;
  }
  const Result r = run({"import", "alog", alog.path(), "--db", import_db_.path()});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find(std::to_string(junk.size()) + " malformed"), std::string::npos) << r.out;
  for (std::size_t line : junk)
    EXPECT_NE(r.out.find("line " + std::to_string(line) + ": "), std::string::npos) << line;
  EXPECT_NE(r.out.find(std::to_string(nav_.size()) + " samples stored"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("mission 1 done"), std::string::npos) << r.out;

  Store s(import_db_.path());
  EXPECT_TRUE(s.integrity_check());
  const auto m = s.missions().get(1);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->status, avk::store::MissionStatus::done);
  EXPECT_EQ(m->status_reason, "imported from " + alog.path());
  EXPECT_EQ(m->name, fs::path(alog.path()).filename().string());
  EXPECT_EQ(m->vehicle_id, fs::path(alog.path()).stem().string());
  const auto config = nlohmann::json::parse(m->config_json);
  EXPECT_EQ(config["kind"], "import");
  EXPECT_EQ(config["source"], "alog");
  EXPECT_EQ(config["names"]["NAV_X"], "NAV_X");
  const auto vehicle = s.vehicles().get(m->vehicle_id);
  ASSERT_TRUE(vehicle);
  EXPECT_EQ(vehicle->kind, "alog");
  double top = 0.0;
  for (const auto& n : nav_)
    top = std::max(top, n.speed_mps);
  EXPECT_DOUBLE_EQ(vehicle->max_speed_mps, top);

  // Navigation is the mission's, sample for sample; guidance is held where the mission had none
  // (an .alog cannot say "no desired heading" once one was posted).
  const auto nav = s.navigation().for_mission(1);
  ASSERT_EQ(nav.size(), nav_.size());
  for (std::size_t i = 0; i < nav.size(); ++i) {
    EXPECT_EQ(nav[i].t_s, nav_[i].t_s);
    EXPECT_EQ(nav[i].x_m, nav_[i].x_m);
    EXPECT_EQ(nav[i].heading_deg, nav_[i].heading_deg);
    EXPECT_EQ(nav[i].speed_mps, nav_[i].speed_mps);
    if (nav_[i].desired_heading_deg) {
      EXPECT_EQ(nav[i].desired_heading_deg, nav_[i].desired_heading_deg);
    }
    EXPECT_EQ(nav[i].helm_mode, "IMPORTED");
  }

  // The same ok turns, cell for cell and sample for sample: the extractor applies the mission's
  // own rules to the samples the mission saw.
  const auto imported = turns_of(s, 1);
  EXPECT_EQ(count(imported, TurnStatus::ok), count(turns_, TurnStatus::ok));
  EXPECT_EQ(count(imported, TurnStatus::rejected), count(turns_, TurnStatus::rejected));
  std::map<double, const avk::store::StoredTurn*> by_start;
  for (const auto& t : imported)
    by_start[t.row.start_time_s] = &t;
  for (const auto& t : turns_) {
    if (t.row.status != TurnStatus::ok) continue;
    ASSERT_TRUE(by_start.count(t.row.start_time_s)) << t.row.start_time_s;
    const auto& i = *by_start.at(t.row.start_time_s);
    EXPECT_EQ(i.row.status, TurnStatus::ok) << i.row.reason;
    EXPECT_EQ(i.row.cell_speed_mps, t.row.cell_speed_mps);
    EXPECT_NEAR(i.row.cell_dheading_deg, t.row.cell_dheading_deg, 1e-9);
    EXPECT_NEAR(i.row.goal_dheading_deg, t.row.goal_dheading_deg, 1e-9);
    EXPECT_EQ(i.raw.samples(), t.raw.samples());
    EXPECT_NEAR(*i.row.advance_m, *t.row.advance_m, 1e-9);
    EXPECT_NEAR(*i.row.transfer_m, *t.row.transfer_m, 1e-9);
    EXPECT_EQ(i.raw.meta().mission_id, "1");
    EXPECT_EQ(i.raw.meta().vehicle_id, m->vehicle_id);
  }
  // The mission aborts a turn when containment takes over; the log shows the same turn ended by
  // the change of desired heading one sample later.
  for (const auto& t : imported) {
    if (t.row.status == TurnStatus::aborted) {
      EXPECT_EQ(t.row.reason, "the desired heading changed before completion");
    }
  }
  EXPECT_NEAR(static_cast<double>(count(imported, TurnStatus::aborted)),
              static_cast<double>(count(turns_, TurnStatus::aborted)), 1.0);
  EXPECT_NE(r.out.find("extracted from desired heading steps: " + std::to_string(imported.size())),
            std::string::npos)
      << r.out;
}

TEST_F(ImportCli, TurnRecordsInTheLogAreImportedExactlyAndReplaceExtraction) {
  TempFile alog("with_records.alog");
  std::size_t corrupt_line = 0;
  {
    AlogWriter w(alog.path());
    // The navigation, with every turn record posted (as pDynamicsMonitor does) at its turn's end.
    std::vector<avk::store::NavRow> nav_part;
    std::size_t next = 0;
    for (const auto& n : nav_) {
      nav_part.push_back(n);
      while (next < turns_.size() && turns_[next].raw.meta().end_time_s <= n.t_s) {
        w.nav_log(nav_part);
        nav_part.clear();
        w.post(n.t_s + 0.01, "TURN_RECORD_RAW", "pDynamicsMonitor",
               avk::kinematics::to_text_record(turns_[next].raw));
        ++next;
        if (next == 3) {
          w.post(n.t_s + 0.02, "TURN_RECORD_RAW", "pDynamicsMonitor",
                 "AVKTURN/1 vehicle_id=x;status=ok");
          corrupt_line = w.line;
        }
      }
    }
    w.nav_log(nav_part);
    ASSERT_EQ(next, turns_.size());
  }
  const Result r = run({"import", "alog", alog.path(), "--db", import_db_.path(), "--vehicle",
                        "m200-alpha", "--names", "NAV_X=NAV_X,DESIRED_SPEED=DESIRED_SPEED"});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("line " + std::to_string(corrupt_line) + ": turn record"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("extracted from desired heading steps: 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("from turn records (TURN_RECORD_RAW): " + std::to_string(turns_.size())),
            std::string::npos)
      << r.out;

  Store s(import_db_.path());
  EXPECT_EQ(s.missions().get(1)->vehicle_id, "m200-alpha");
  EXPECT_EQ(s.navigation().for_mission(1).size(), nav_.size());
  const auto imported = turns_of(s, 1);
  ASSERT_EQ(imported.size(), turns_.size());
  for (std::size_t i = 0; i < imported.size(); ++i) {
    EXPECT_EQ(imported[i].raw, turns_[i].raw) << i;
    EXPECT_EQ(imported[i].row.status, turns_[i].row.status);
    EXPECT_EQ(imported[i].row.reason, turns_[i].row.reason);
    EXPECT_EQ(imported[i].normalized.has_value(), turns_[i].normalized.has_value());
  }
}

TEST(ImportCliErrors, UsageErrorsAndAMissingFile) {
  TempDb db("avk_import_errors");
  EXPECT_EQ(run({"import"}).rc, 2);
  EXPECT_EQ(run({"import", "csv", "x", "--db", db.path()}).rc, 2);
  EXPECT_EQ(run({"import", "alog", "--db", db.path()}).rc, 2);
  EXPECT_EQ(run({"import", "alog", "a.alog"}).rc, 2);
  EXPECT_EQ(run({"import", "alog", "a.alog", "--db", db.path(), "--names", "NAV_Q=X"}).rc, 2);
  EXPECT_EQ(run({"import", "alog", "a.alog", "--db", db.path(), "--threshold", "-1"}).rc, 2);
  EXPECT_EQ(run({"import", "alog", "a.alog", "--db", db.path(), "--max-yaw-rate", "x"}).rc, 2);
  const Result missing = run({"import", "alog", "/nonexistent/dir/x.alog", "--db", db.path()});
  EXPECT_EQ(missing.rc, 1);
  EXPECT_NE(missing.err.find("cannot open '/nonexistent/dir/x.alog'"), std::string::npos)
      << missing.err;
  EXPECT_EQ(run({"import", "alog", fs::temp_directory_path().string(), "--db", db.path()}).rc, 1);
  EXPECT_TRUE(Store(db.path()).missions().list().empty());
}

TEST(ImportCliBatches, ALongStraightRunIsStoredInBatchesWithRenamedVariables) {
  TempDb db("avk_import_batches");
  TempFile alog("long_run.alog");
  constexpr int kSamples = 12'345;  // three batches
  {
    std::ofstream out(alog.path(), std::ios::binary);
    out << "%% a log with vehicle-specific names, CRLF line ends and a torn last line\r\n";
    for (int i = 0; i < kSamples; ++i) {
      const std::string t = num(i * 0.1);
      out << t << " GPS_X gpsd " << num(i * 0.1 * 1.2) << "\r\n"
          << t << " GPS_Y gpsd 5\r\n"
          << t << " COMPASS compass 90\r\n"
          << t << " GPS_SPEED gpsd 1.2\r\n";
    }
    out << "1234.5 GPS_X gp";
  }
  const Result r =
      run({"import", "alog", alog.path(), "--db", db.path(), "--vehicle", "kf", "--names",
           "NAV_X=GPS_X,NAV_Y=GPS_Y,NAV_HEADING=COMPASS,NAV_SPEED=GPS_SPEED"});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 malformed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line " + std::to_string(4 * kSamples + 2) + ": expected time"),
            std::string::npos)
      << r.out;
  Store s(db.path());
  const auto nav = s.navigation().for_mission(1);
  ASSERT_EQ(nav.size(), static_cast<std::size_t>(kSamples));
  EXPECT_DOUBLE_EQ(nav.back().x_m, (kSamples - 1) * 0.1 * 1.2);
  EXPECT_FALSE(nav.back().desired_heading_deg);
  EXPECT_DOUBLE_EQ(s.vehicles().get("kf")->max_speed_mps, 1.2);
  EXPECT_EQ(nlohmann::json::parse(s.missions().get(1)->config_json)["names"]["NAV_HEADING"],
            "COMPASS");
  EXPECT_TRUE(turns_of(s, 1).empty());
}

}  // namespace
