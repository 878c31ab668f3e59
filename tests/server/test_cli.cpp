#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_text.hpp"
#include "server/cli/cli.hpp"
#include "server/cli/usage.hpp"
#include "support/cli_run.hpp"
#include "support/synthetic_turns.hpp"

namespace fs = std::filesystem;

namespace {

using avk::testing::example;
using avk::testing::run;
using Result = avk::testing::CliResult;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class CliFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("avk_cli_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream turns(path("turns.txt"));
    turns << "# two cells, two turns each\n";
    unsigned seed = 1;
    for (double d : {40.0, 90.0}) {
      for (int r = 0; r < 2; ++r) {
        avk::testing::ArcTurnSpec s;
        s.dheading_deg = r ? -d : d;
        s.seed = seed++;
        s.start = {5.0 * seed, 1.0, 20.0 * seed};
        s.position_noise_m = 0.02;
        turns << avk::kinematics::to_text_record(avk::testing::make_arc_turn(s)) << "\n";
      }
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

}  // namespace

TEST(Cli, UnknownCommandIsAnErrorThatNamesIt) {
  const Result r = run({"frobnicate"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("frobnicate"), std::string::npos);
}

// Regression: `avk predict --help` was "unknown option --help"; only `avk --help` printed the
// usage. Every command and subcommand the CLI knows answers --help and -h with its own usage on
// stdout and exit 0, also after other words (even wrong ones), and without doing anything else.
TEST(Cli, EveryCommandAndSubcommandAnswersHelpWithItsOwnUsage) {
  using avk::server::command_usages;
  // Should help not be recognised, nothing may start for real: `avk serve -h` would open the
  // default database (under XDG_DATA_HOME, here a path that cannot be made) and listen.
  const char* data_home = std::getenv("XDG_DATA_HOME");
  const std::string saved = data_home ? data_home : "";
  ::setenv("XDG_DATA_HOME", "/dev/null/avk-test-no-data", 1);
  const std::vector<std::string> others{"--db", "/dev/null/avk-test-no.db", "--no-such-option"};
  const auto own_usage_only = [](const Result& r, const std::string& line,
                                 const std::string& command, const std::string& label) {
    EXPECT_EQ(r.rc, 0) << label << ": " << r.err;
    EXPECT_EQ(r.err, "") << label;
    EXPECT_NE(r.out.find("  " + line + " "), std::string::npos) << label << ":\n" << r.out;
    // Only this command's lines: every usage line names it.
    std::istringstream lines(r.out);
    for (std::string l; std::getline(lines, l);) {
      if (l.rfind("  avk ", 0) == 0) {
        EXPECT_EQ(l.rfind("  avk " + command + " ", 0), 0u) << label << ": " << l;
      }
    }
  };
  std::size_t walked = 0;
  for (const auto& u : command_usages()) {
    const std::string command(u.command);
    for (const char* help : {"--help", "-h"}) {
      own_usage_only(run({command, help}), "avk " + command, command, command + " " + help);
      if (u.subcommands.empty()) {
        std::vector<std::string> words{command};
        words.insert(words.end(), others.begin(), others.end());
        words.push_back(help);
        own_usage_only(run(words), "avk " + command, command, command + " ... " + help);
        ++walked;
      }
      for (const auto sub_view : u.subcommands) {
        const std::string sub(sub_view);
        const std::string label = command + " " + sub + " " + help;
        std::vector<std::string> after_others{command, sub};
        after_others.insert(after_others.end(), others.begin(), others.end());
        after_others.push_back(help);
        for (const auto& words : {std::vector<std::string>{command, sub, help}, after_others}) {
          const Result r = run(words);
          own_usage_only(r, "avk " + command + " " + sub, command, label);
          // This subcommand's usage, not its siblings' (a line documenting several names it).
          std::istringstream lines(r.out);
          for (std::string l; std::getline(lines, l);) {
            if (l.rfind("  avk ", 0) == 0) {
              EXPECT_NE(l.find(sub), std::string::npos) << label << ": " << l;
            }
          }
        }
        ++walked;
      }
    }
  }
  // A usage per subcommand it documents (or per command without any), twice: 38 today.
  EXPECT_GE(walked, 2u * 38u);
  // `avk --help` holds every usage; an unknown subcommand stays an error.
  const Result all = run({"--help"});
  EXPECT_EQ(all.rc, 0);
  for (const auto& u : command_usages())
    EXPECT_NE(all.out.find(u.text), std::string::npos) << u.text;
  const Result unknown = run({"mission", "frobnicate", "--help"});
  EXPECT_EQ(unknown.rc, 2);
  EXPECT_NE(unknown.err.find("frobnicate"), std::string::npos) << unknown.err;
  if (data_home) {
    ::setenv("XDG_DATA_HOME", saved.c_str(), 1);
  } else {
    ::unsetenv("XDG_DATA_HOME");
  }
}

TEST(Cli, UnknownOptionAndBadNumberAreUsageErrors) {
  Result r = run({"ckt", "query", "--ckt", "x.json", "--sped", "1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--sped"), std::string::npos);
  r = run({"ckt", "query", "--ckt", "x.json", "--speed", "fast", "--dheading", "10"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--speed"), std::string::npos);
  r = run({"ckt", "query", "--ckt", "x.json", "--speed", "nan", "--dheading", "10"});
  EXPECT_EQ(r.rc, 2);
}

TEST_F(CliFiles, TurnNormalizeMakesRightTurnsFromTheOrigin) {
  const Result r = run({"turn", "normalize", path("turns.txt")});
  ASSERT_EQ(r.rc, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  int n = 0;
  while (std::getline(lines, line)) {
    const auto t = avk::kinematics::parse_text_record(line);
    EXPECT_TRUE(t.meta().normalized);
    EXPECT_DOUBLE_EQ(t.samples().front().x_m, 0.0);
    EXPECT_GT(t.samples().back().x_m, 0.0);
    ++n;
  }
  EXPECT_EQ(n, 4);
  const Result j = run({"turn", "normalize", "-", "--format", "json"}, slurp(path("turns.txt")));
  ASSERT_EQ(j.rc, 0) << j.err;
  EXPECT_EQ(j.out.rfind("{", 0), 0u);
}

TEST_F(CliFiles, BadTurnRecordNamesFileAndLine) {
  std::ofstream(path("turns.txt"), std::ios::app) << "AVKTURN/1 garbage\n";
  const Result r = run({"ckt", "build", "--turns", path("turns.txt"), "--out", path("ckt.json")});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("turns.txt:6:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("ckt.json")));
}

TEST_F(CliFiles, BuildImportQueryExport) {
  Result r = run({"ckt", "build", "--turns", path("turns.txt"), "--out", path("ckt.json"),
                  "--vehicle", "boat-7"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string written = slurp(path("ckt.json"));
  const auto table = avk::kinematics::parse_ckt_json(written);
  EXPECT_EQ(table.vehicle_id, "boat-7");
  EXPECT_EQ(table.cells().size(), 2u);

  r = run({"ckt", "import", path("ckt.json"), "--out", path("again.json")});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("2 cells with turns, 4 turns"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("again.json")), written);

  r = run({"ckt", "query", "--ckt", path("ckt.json"), "--speed", "1", "--dheading", "-65"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frame"], "normalized");
  EXPECT_LT(j["trajectory"].back()[0].get<double>(), 0.0);  // a left turn ends to port

  r = run({"ckt", "query", "--ckt", path("ckt.json"), "--speed", "1", "--dheading", "90", "--x",
           "100", "--y", "50", "--heading", "90", "--format", "csv"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("0,100.0,50.0\n"), std::string::npos) << r.out;

  r = run({"ckt", "export", "--ckt", path("ckt.json"), "--format", "csv"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out.rfind("speed_mps,dheading_deg,vertex_index,x_m,y_m\n", 0), 0u);
}

TEST_F(CliFiles, OutOfRangeSpeedIsRefused) {
  ASSERT_EQ(run({"ckt", "build", "--turns", path("turns.txt"), "--out", path("ckt.json")}).rc, 0);
  const Result r =
      run({"ckt", "query", "--ckt", path("ckt.json"), "--speed", "2", "--dheading", "10"});
  EXPECT_EQ(r.rc, 1);
  // Named with the table's range: every parameter out of range is reported with its range.
  EXPECT_NE(r.err.find("speed: 2.0 m/s is outside the table's speed range [1.0, 1.0] m/s"),
            std::string::npos)
      << r.err;
}

TEST_F(CliFiles, CorruptCktIsRefusedAndExistingOutputKept) {
  ASSERT_EQ(run({"ckt", "build", "--turns", path("turns.txt"), "--out", path("ckt.json")}).rc, 0);
  const std::string good = slurp(path("ckt.json"));
  std::string bad = good;
  bad.replace(bad.find("\"schema_version\": 4"), 19, "\"schema_version\": 9");
  std::ofstream(path("bad.json")) << bad;
  Result r = run({"ckt", "import", path("bad.json"), "--out", path("ckt.json")});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("schema_version"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("ckt.json")), good);  // the existing file is untouched
  std::ofstream(path("trunc.json")) << good.substr(0, good.size() / 3);
  r = run({"ckt", "import", path("trunc.json")});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("line"), std::string::npos) << r.err;
  r = run({"ckt", "import", path("missing.json")});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
}

TEST(CliSim, TurnPrintsTheTrajectoryCsv) {
  const Result r = run({"sim", "turn", "--speed", "1", "--dheading", "-40", "--ticks",
                        "plant=4,controller=4,helm=4"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out.rfind("t_s,x_m,y_m,heading_deg,speed_mps,desired_heading_deg,desired_speed_mps,"
                        "rudder_pct,thrust_pct\n",
                        0),
            0u);
  EXPECT_NE(r.err.find("completed"), std::string::npos);
  EXPECT_GT(std::count(r.out.begin(), r.out.end(), '\n'), 100);
}

TEST(CliSim, BadInputIsNamed) {
  Result r = run({"sim", "turn", "--speed", "9", "--dheading", "40"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("maximum"), std::string::npos) << r.err;
  r = run({"sim", "turn", "--speed", "1", "--dheading", "40", "--vehicle", "blimp"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("blimp"), std::string::npos) << r.err;
  r = run({"sim", "turn", "--speed", "1", "--dheading", "40", "--ticks", "plant=0"});
  EXPECT_EQ(r.rc, 2);
  r = run({"sim", "turn", "--speed", "1", "--dheading", "200"});
  EXPECT_EQ(r.rc, 2);
}

TEST(CliSim, VariabilityReportsTheCoefficientOfVariation) {
  const Result r =
      run({"sim", "variability", "--speed", "1", "--dheading", "90", "--repeats", "5", "--jitter"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("repetition,seed,completed,advance_m,transfer_m\n"), std::string::npos);
  EXPECT_NE(r.out.find("(CV "), std::string::npos);
}

// A vehicle id from the command line is bounded like every vehicle id, before anything runs.
TEST(CliMission, AVehicleIdTooLongIsAUsageErrorNamingTheOption) {
  const std::string id(65, 'v');
  for (const auto& vehicle :
       {std::vector<std::string>{"--sim"}, std::vector<std::string>{"--m200", "127.0.0.1:1"}}) {
    std::vector<std::string> words{"mission",      "run",
                                   "--config",     example("thesis-fig4-1.json"),
                                   "--db",         "/nonexistent-avk-dir/x.db",
                                   "--vehicle-id", id};
    words.insert(words.end(), vehicle.begin(), vehicle.end());
    const Result r = run(words);
    EXPECT_EQ(r.rc, 2) << vehicle[0] << ": " << r.err;
    EXPECT_NE(r.err.find("--vehicle-id must be at most 64 bytes"), std::string::npos) << r.err;
  }
}

TEST(CliMission, ValidateNamesEveryProblem) {
  Result r = run({"mission", "validate", "--config",
                  std::string(AVK_SOURCE_DIR) + "/examples/thesis-fig4-1.json"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("(18 turns)"), std::string::npos) << r.out;
  r = run({"mission", "validate", "--config", "-"},
          R"({"name": "x", "turn_array": {"speeds_mps": [9], "dheadings_deg": [0]},
              "operating_region": {"polygon_m": [[0,0],[50,0],[50,50],[0,50]], "buffer_m": 5,
                                   "return_point_m": [25, 25]}})");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("/turn_array/speeds_mps/0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/turn_array/dheadings_deg/0"), std::string::npos) << r.err;
}
