// `avk mission run|resume|list|report` and `avk ckt build|export --db` end to end on the
// simulator, including a kill -9 of a running mission process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "kinematics/ckt_file.hpp"
#include "server/cli/cli.hpp"
#include "store/store.hpp"
#include "support/cli_run.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_db.hpp"

namespace fs = std::filesystem;
using avk::store::Store;
using avk::testing::TempDb;
using nlohmann::json;

namespace {

using avk::testing::example;
using avk::testing::run;
using Result = avk::testing::CliResult;

std::int64_t count_turns(Store& s, std::optional<avk::kinematics::TurnStatus> status) {
  avk::store::TurnFilter f;
  f.status = status;
  f.limit = 100000;
  return static_cast<std::int64_t>(s.turns().list(f).size());
}

// Per (speed, dheading) cell of the CKT: advance and transfer means.
std::map<std::pair<double, double>, std::pair<double, double>> cell_means(
    const std::string& json_text) {
  const auto table = avk::kinematics::parse_ckt_json(json_text);
  std::map<std::pair<double, double>, std::pair<double, double>> out;
  for (const auto& c : table.cells()) {
    if (c.has_data()) out[{c.speed_mps, c.dheading_deg}] = {c.advance_m.mean, c.transfer_m.mean};
  }
  return out;
}

class MissionCli : public ::testing::Test {
 protected:
  TempDb db_{"avk_mission_cli"};

  // The Figure 4-1 mission (changed by `edit`) with the fixed 5 deg completion threshold it had
  // before completion became relative to the commanded change (completion_fraction 1 gives
  // min(5, |goal|) = 5 deg for every heading change of the grid), written next to the database.
  // The direction and table-shape scenarios below were laid out on that timeline:
  // which turn meets the buffer, and the GNSS noise each single M200 turn of a cell draws, follow
  // from how long every earlier turn took. What they test does not depend on how a 10 deg turn
  // ends, which test_small_turns.cpp covers.
  std::string fixed_threshold_mission(const std::string& tag,
                                      const std::function<void(json&)>& edit = {}) {
    json doc;
    std::ifstream(example("thesis-fig4-1.json")) >> doc;
    doc["constant_heading"]["completion_fraction"] = 1.0;
    if (edit) edit(doc);
    const fs::path path = fs::path(db_.path()).replace_extension("." + tag + ".json");
    std::ofstream(path) << doc.dump();
    written_.push_back(path);
    return path.string();
  }
  void TearDown() override {
    std::error_code ec;
    for (const auto& p : written_)
      fs::remove(p, ec);
  }

 private:
  std::vector<fs::path> written_;
};

TEST_F(MissionCli, Figure41OnUsimCompletesEveryTurnAndStoresEverything) {
  const Result r = run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db",
                        db_.path(), "--sim", "--vehicle", "usim"});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("18/18 turns ok"), std::string::npos) << r.out;
  Store s(db_.path());
  EXPECT_TRUE(s.integrity_check());
  const auto missions = s.missions().list();
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_EQ(missions[0].status, avk::store::MissionStatus::done);
  EXPECT_FALSE(missions[0].runner_pid.has_value());
  EXPECT_EQ(count_turns(s, avk::kinematics::TurnStatus::ok), 18);
  // Every cell once, each with its normalised form and a ConditionSet time.
  const auto cells = s.missions().cell_stats(missions[0].id);
  ASSERT_EQ(cells.size(), 18u);
  for (const auto& c : cells) {
    EXPECT_EQ(c.n_ok, 1) << c.speed_mps << " " << c.dheading_deg;
    ASSERT_TRUE(c.condition_set_time_s.has_value());
    EXPECT_GT(c.condition_set_time_s->mean, 0.0);
  }
  // Aborted turns are stored too; ok + aborted + rejected is everything recorded.
  const auto all = count_turns(s, std::nullopt);
  EXPECT_EQ(all, 18 + count_turns(s, avk::kinematics::TurnStatus::aborted) +
                     count_turns(s, avk::kinematics::TurnStatus::rejected));
  // The navigation log has every mode of the mission, in time order.
  const auto nav = s.navigation().for_mission(missions[0].id);
  ASSERT_GT(nav.size(), 1000u);
  std::set<std::string> modes;
  for (std::size_t i = 0; i < nav.size(); ++i) {
    modes.insert(nav[i].helm_mode);
    if (i) {
      EXPECT_GE(nav[i].t_s, nav[i - 1].t_s);
    }
  }
  for (const char* m : {"CONDITIONING", "TURNING", "RETURNING"})
    EXPECT_TRUE(modes.count(m)) << m;
  // The mission ends at the return point.
  EXPECT_LT(std::hypot(nav.back().x_m - 0.0, nav.back().y_m + 70.0), 10.0);

  const Result report = run({"mission", "report", "1", "--db", db_.path(), "--format", "json"});
  ASSERT_EQ(report.rc, 0) << report.err;
  const json j = json::parse(report.out);
  EXPECT_EQ(j["status"], "done");
  EXPECT_EQ(j["turns"]["ok"], 18);
  EXPECT_EQ(j["cells"].size(), 18u);
  EXPECT_GT(j["condition_set"]["time_to_set_s"]["mean"].get<double>(), 0.0);
  const Result list = run({"mission", "list", "--db", db_.path()});
  EXPECT_NE(list.out.find("done"), std::string::npos);
  EXPECT_NE(list.out.find("thesis-fig4-1"), std::string::npos);

  // Turns are numbered one way (k/N) and the database id is called an id; each turn
  // shows its side; a cell of one turn shows its value without a "± 0.00" spread.
  EXPECT_EQ(r.out.find(", turn "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", id "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("turn   18/18"), std::string::npos) << r.out;
  const Result table = run({"mission", "report", "1", "--db", db_.path()});
  ASSERT_EQ(table.rc, 0) << table.err;
  EXPECT_EQ(table.out.find("± 0.00"), std::string::npos) << table.out;
  // The turn list: id, speed, then the signed goal; the mission alternates sides.
  EXPECT_TRUE(std::regex_search(table.out, std::regex(R"(\n\s+\d+\s+\d\.\d\d\s+\+\d+\s+ok)")))
      << table.out;
  EXPECT_TRUE(std::regex_search(table.out, std::regex(R"(\n\s+\d+\s+\d\.\d\d\s+-\d+\s+ok)")))
      << table.out;
  // `mission wait` replays what is stored and says how the mission ended.
  const Result waited = run({"mission", "wait", "1", "--db", db_.path()});
  ASSERT_EQ(waited.rc, 0) << waited.out << waited.err;
  std::istringstream lines(waited.out);
  std::string line;
  int turn_lines = 0;
  std::string last;
  while (std::getline(lines, line)) {
    if (line.rfind("turn ", 0) == 0) ++turn_lines;
    last = line;
  }
  EXPECT_EQ(turn_lines, all) << waited.out;
  EXPECT_NE(waited.out.find("turn   18/18"), std::string::npos) << waited.out;
  EXPECT_NE(last.find("finished: done"), std::string::npos) << last;
  EXPECT_NE(last.find("18/18 turns ok"), std::string::npos) << last;
}

TEST_F(MissionCli, CatamaranInCurrentAndWindIsContainedAndLosesNoTurn) {
  // Seed 2: with the example's own seed 1 the M200 happens to keep every turn out of the buffer;
  // with 2 the current carries one 1.5 m/s turn into it (seeds 2-6 all have one or two).
  const Result r =
      run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(), "--sim",
           "--sim-config", example("sim-choppy.json"), "--seed", "2"});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  Store s(db_.path());
  EXPECT_EQ(count_turns(s, avk::kinematics::TurnStatus::ok), 18);
  // Containment aborted at least one turn, which was stored with its reason and run again.
  avk::store::TurnFilter f;
  f.status = avk::kinematics::TurnStatus::aborted;
  const auto aborted = s.turns().list(f);
  ASSERT_FALSE(aborted.empty());
  for (const auto& t : aborted) {
    EXPECT_EQ(t.reason.rfind("containment", 0), 0u) << t.reason;
    avk::store::TurnFilter same;
    same.speed_mps = t.commanded_speed_mps;
    same.dheading_deg = t.goal_dheading_deg;
    same.status = avk::kinematics::TurnStatus::ok;
    same.after_id = t.id;  // the retry comes after the abort
    EXPECT_EQ(s.turns().list(same).size(), 1u);
  }
  const auto events = s.missions().events(1);
  EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                          [](const auto& e) { return e.kind == "containment"; }));
  // In wind and current the catamaran overshoots and swings; no turn may start in a swing: the
  // report lists every turn with its heading error and yaw rate at the start.
  const Result report = run({"mission", "report", "1", "--db", db_.path(), "--format", "json"});
  ASSERT_EQ(report.rc, 0) << report.err;
  const json j = json::parse(report.out);
  int ok_turns = 0;
  for (const json& t : j["turn_list"]) {
    if (t["status"] != "ok") continue;
    ++ok_turns;
    EXPECT_LE(std::abs(t["start_heading_error_deg"].get<double>()), 2.0) << t.dump();
    EXPECT_LE(std::abs(t["start_yaw_rate_dps"].get<double>()), 1.0) << t.dump();
  }
  EXPECT_EQ(ok_turns, 18);
  const Result text = run({"mission", "report", "1", "--db", db_.path()});
  EXPECT_NE(text.out.find("start heading err"), std::string::npos) << text.out;
  // The recorder judged the steady stretches in the current as the mission ran: the M200's loop
  // holds the speed over ground (identified, or the default when the legs could not tell).
  const Result motion = run({"vehicle", "motion", "--db", db_.path(), "--format", "json"});
  ASSERT_EQ(motion.rc, 0) << motion.err;
  const json m = json::parse(motion.out);
  EXPECT_EQ(m["speed_reference"]["value"], "over_ground") << m.dump();
  EXPECT_EQ(m["drift_scatter"]["source"], "measured") << m.dump();
  EXPECT_GT(m["drift_scatter"]["legs"].get<int>(), 0);
  EXPECT_TRUE(m["current"].is_object()) << m.dump();
  const Result estimate =
      run({"current", "estimate", "--db", db_.path(), "--mission", "1", "--format", "json"});
  ASSERT_EQ(estimate.rc, 0) << estimate.err;
  const json e = json::parse(estimate.out);
  EXPECT_TRUE(e["speed_reference"].is_object()) << e.dump();
  EXPECT_GT(e["motion_legs"].get<int>(), 0);
  const Result motion_text = run({"vehicle", "motion", "--db", db_.path()});
  EXPECT_NE(motion_text.out.find("speed reference: over_ground"), std::string::npos)
      << motion_text.out;
  EXPECT_EQ(run({"vehicle"}).rc, 2);
  EXPECT_EQ(run({"vehicle", "motion", "--db", db_.path(), "--vehicle", "nobody"}).rc, 1);
}

TEST_F(MissionCli, ExportedTableGrowsWithSpeedAndHeadingChangeAsPhysicsSays) {
  // The Heron's yaw damping does not grow with speed, so its yaw rate is bounded by the hull and
  // its turning circle widens with speed: advance grows with speed for every heading change,
  // transfer for the large ones. (The M200's hull-lift damping grows with speed and keeps its
  // turning circle nearly the same at every speed, so this ordering is the Heron's.)
  ASSERT_EQ(run({"mission", "run", "--config", fixed_threshold_mission("fixed"), "--db", db_.path(),
                 "--sim", "--vehicle", "catamaran:heron", "--quiet"})
                .rc,
            0);
  const fs::path out = fs::path(db_.path()).replace_extension(".ckt.json");
  const Result built = run({"ckt", "build", "--db", db_.path(), "--out", out.string()});
  ASSERT_EQ(built.rc, 0) << built.err;
  std::ifstream f(out);
  std::stringstream text;
  text << f.rdbuf();
  const auto m = cell_means(text.str());
  ASSERT_EQ(m.size(), 18u);
  // One turn a cell under GNSS noise of σ 0.3 m: a 40° turn recorded to 5° of its goal is about
  // 2 m long, so its advance is ordered within that noise.
  constexpr double kGnssSigma_m = 0.3;
  for (double d : {40.0, 70.0, 100.0, 130.0, 160.0}) {
    EXPECT_LT(m.at({0.5, d}).first, m.at({1.0, d}).first + kGnssSigma_m) << d;
    EXPECT_LT(m.at({1.0, d}).first, m.at({1.5, d}).first + kGnssSigma_m) << d;
  }
  EXPECT_LT(m.at({0.5, 100.0}).first, m.at({1.5, 100.0}).first);
  for (double d : {100.0, 130.0, 160.0}) {
    EXPECT_LT(m.at({0.5, d}).second, m.at({1.0, d}).second) << d;
    EXPECT_LT(m.at({1.0, d}).second, m.at({1.5, d}).second) << d;
  }
  for (double d : {10.0, 40.0, 70.0, 100.0})
    EXPECT_LT(m.at({1.5, d}).second, m.at({1.5, d + 30.0}).second) << d;
  fs::remove(out);
}

TEST_F(MissionCli, UsimTransferGrowsWithHeadingChange) {
  ASSERT_EQ(run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(),
                 "--sim", "--quiet"})
                .rc,
            0);
  const Result csv = run({"ckt", "export", "--db", db_.path(), "--format", "json"});
  ASSERT_EQ(csv.rc, 0) << csv.err;
  const auto m = cell_means(csv.out);
  for (double u : {0.5, 1.0, 1.5}) {
    // Up to 130 deg the vehicle is still moving to the turn side when the turn completes.
    for (double d : {10.0, 40.0, 70.0, 100.0})
      EXPECT_LT(m.at({u, d}).second, m.at({u, d + 30.0}).second) << u << " " << d;
    // Completion within 10 % of the change: the heading closes on its goal at about the same
    // rate whatever the change, so a 10 deg turn runs as long as a 40 deg one (measured: 18.4 m
    // of advance against 14.9-15.2 m) while barely bending.
    EXPECT_GT(m.at({u, 10.0}).first, m.at({u, 40.0}).first);
    // Past 90 deg the vehicle comes back along its original course: advance falls.
    EXPECT_GT(m.at({u, 100.0}).first, m.at({u, 160.0}).first);
  }
}

TEST_F(MissionCli, DirectionAutoLosesFewerTurnsToContainmentThanAlternate) {
  // The side chosen alone: the helm's foresight (turning back before a short run ahead) is off,
  // or neither mission would meet the buffer.
  const auto no_foresight = [](json& doc) { doc["condition_set"]["run_ahead_s"] = 0; };
  const std::string alternate_config = fixed_threshold_mission("alternate", no_foresight);
  const fs::path auto_config = fixed_threshold_mission("auto", [&](json& doc) {
    no_foresight(doc);
    doc["turn_array"]["direction"] = "auto";
  });
  ASSERT_EQ(
      run({"mission", "run", "--config", alternate_config, "--db", db_.path(), "--sim", "--quiet"})
          .rc,
      0);
  ASSERT_EQ(run({"mission", "run", "--config", auto_config.string(), "--db", db_.path(), "--sim",
                 "--quiet"})
                .rc,
            0);
  Store s(db_.path());
  std::int64_t aborted[2] = {0, 0};
  std::set<double> sides;
  for (std::int64_t m : {1, 2}) {
    for (const auto& c : s.missions().cell_stats(m)) {
      EXPECT_EQ(c.n_ok, 1);
      aborted[m - 1] += c.n_aborted;
    }
  }
  // The thesis' alternating mission runs into the buffer twice on this region; auto never does.
  EXPECT_GT(aborted[0], 0);
  EXPECT_LT(aborted[1], aborted[0]);
  // Auto still turns both ways.
  avk::store::TurnFilter f;
  f.mission_id = 2;
  for (const auto& t : s.turns().list(f))
    sides.insert(t.goal_dheading_deg > 0 ? 1.0 : -1.0);
  EXPECT_EQ(sides.size(), 2u);
}

TEST_F(MissionCli, InvalidMissionNamesTheFieldAndStoresNothing) {
  const fs::path bad = fs::path(db_.path()).replace_extension(".mission.json");
  std::ofstream(bad)
      << R"({"name": "x", "turn_array": {"speeds_mps": [9.0], "dheadings_deg": [200]},
    "operating_region": {"polygon_m": [[0,0],[10,0],[0,10],[10,10]], "return_point_m": [1, 1]}})";
  const Result r = run({"mission", "run", "--config", bad.string(), "--db", db_.path(), "--sim"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("/turn_array/speeds_mps/0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/turn_array/dheadings_deg/0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/operating_region/polygon_m"), std::string::npos) << r.err;
  Store s(db_.path());
  EXPECT_TRUE(s.missions().list().empty());
  fs::remove(bad);
}

TEST_F(MissionCli, UsageErrorsNameTheProblem) {
  EXPECT_EQ(
      run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path()}).rc, 2);
  EXPECT_EQ(run({"mission", "report", "x1", "--db", db_.path()}).rc, 2);
  const Result missing = run({"mission", "report", "7", "--db", db_.path()});
  EXPECT_EQ(missing.rc, 1);
  EXPECT_NE(missing.err.find("no mission 7"), std::string::npos);
  ASSERT_EQ(run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(),
                 "--sim", "--quiet"})
                .rc,
            0);
  const Result again = run({"mission", "resume", "1", "--db", db_.path(), "--sim"});
  EXPECT_EQ(again.rc, 1);
  EXPECT_NE(again.err.find("nothing to resume"), std::string::npos) << again.err;
  // Two vehicles in one database: the table needs to be told which.
  ASSERT_EQ(run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(),
                 "--sim", "--vehicle", "catamaran", "--quiet"})
                .rc,
            0);
  const Result mixed = run({"ckt", "build", "--db", db_.path()});
  EXPECT_EQ(mixed.rc, 2);
  EXPECT_NE(mixed.err.find("--vehicle"), std::string::npos) << mixed.err;
  const Result one = run({"ckt", "build", "--db", db_.path(), "--mission", "2"});
  EXPECT_EQ(one.rc, 0) << one.err;
  EXPECT_EQ(avk::kinematics::parse_ckt_json(one.out).vehicle_id, "sim-catamaran:m200");
}

TEST_F(MissionCli, PersistentExcitationLogsNavigationForIdentification) {
  const Result r = run({"mission", "run", "--config", example("persistent-excitation.json"), "--db",
                        db_.path(), "--sim", "--quiet"});
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  Store s(db_.path());
  const auto nav = s.navigation().for_mission(1);
  std::size_t exciting = 0;
  std::set<double> desired;
  for (const auto& n : nav) {
    if (n.helm_mode != "EXCITING") continue;
    ++exciting;
    if (n.desired_heading_deg) desired.insert(*n.desired_heading_deg);
  }
  // 900 s of excitation at 4 Hz navigation, with a new heading every 3 to 10 s.
  EXPECT_GT(exciting, 3000u);
  EXPECT_GT(desired.size(), 60u);
  EXPECT_EQ(count_turns(s, std::nullopt), 0);
}

// --- a real process, killed -------------------------------------------------------------

using avk::testing::spawn_avk;

// Waits (bounded) until the running mission has stored at least n ok turns.
bool wait_for_ok_turns(const std::string& db, std::int64_t n, pid_t child) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(child, nullptr, WNOHANG) == child) return false;  // ended early
    if (fs::exists(db)) {
      try {
        Store s(db);
        if (count_turns(s, avk::kinematics::TurnStatus::ok) >= n) return true;
      } catch (const std::exception&) {
        // The schema is being created; look again.
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST_F(MissionCli, KillNineLosesNoFinishedTurnAndResumeCompletesTheMission) {
  const std::string log = db_.path() + ".log";
  const pid_t child =
      spawn_avk({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(),
                 "--sim", "--realtime", "--realtime-factor", "60"},
                log);
  ASSERT_GT(child, 0);
  ASSERT_TRUE(wait_for_ok_turns(db_.path(), 4, child)) << "the mission did not store 4 turns";
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));

  std::vector<avk::store::StoredTurn> before;
  {
    Store s(db_.path());
    EXPECT_TRUE(s.integrity_check());
    avk::store::TurnFilter f;
    f.limit = 1000;
    for (const auto& row : s.turns().list(f))
      before.push_back(*s.turns().get(row.id));
    ASSERT_GE(before.size(), 4u);
    EXPECT_EQ(s.missions().get(1)->status, avk::store::MissionStatus::running);  // as it was left
    EXPECT_GT(s.navigation().for_mission(1).size(), 100u);
  }
  const Result list = run({"mission", "list", "--db", db_.path()});
  EXPECT_NE(list.out.find("interrupted"), std::string::npos) << list.out;

  const Result resumed = run({"mission", "resume", "1", "--db", db_.path(), "--sim"});
  ASSERT_EQ(resumed.rc, 0) << resumed.out << resumed.err;
  Store s(db_.path());
  EXPECT_TRUE(s.integrity_check());
  EXPECT_EQ(count_turns(s, avk::kinematics::TurnStatus::ok), 18);
  const auto cells = s.missions().cell_stats(1);
  for (const auto& c : cells)
    EXPECT_EQ(c.n_ok, 1) << c.speed_mps << " " << c.dheading_deg;
  for (const auto& t : before) {
    const auto now = s.turns().get(t.row.id);
    ASSERT_TRUE(now.has_value());
    EXPECT_EQ(now->raw, t.raw);
  }
  // The resumed clock continues after everything stored before the kill.
  const auto nav = s.navigation().for_mission(1);
  for (std::size_t i = 1; i < nav.size(); ++i)
    ASSERT_GE(nav[i].t_s, nav[i - 1].t_s);
  EXPECT_EQ(s.missions().get(1)->status, avk::store::MissionStatus::done);
  fs::remove(log);
}

TEST_F(MissionCli, SigtermStopsTheMissionAsInterruptedAndResumable) {
  const std::string log = db_.path() + ".log";
  const pid_t child =
      spawn_avk({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", db_.path(),
                 "--sim", "--realtime", "--realtime-factor", "60"},
                log);
  ASSERT_GT(child, 0);
  ASSERT_TRUE(wait_for_ok_turns(db_.path(), 2, child));
  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  Store s(db_.path());
  const auto m = s.missions().get(1);
  EXPECT_EQ(m->status, avk::store::MissionStatus::interrupted);
  EXPECT_FALSE(m->runner_pid.has_value());
  EXPECT_NE(m->status_reason.find("signal"), std::string::npos);
  fs::remove(log);
}

}  // namespace
