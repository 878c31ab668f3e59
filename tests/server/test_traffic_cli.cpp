// `avk traffic`: the simulated traffic source of the simulator deployment, a real `avk traffic`
// process sending a scenario's contacts as AIVDM over UDP to a real gpsd; every contact arrives
// through gpsd with its position report and its name, as a real receiver's would. Then, a station
// watching that gpsd shows the contacts in GET /traffic.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <set>

#include "sim/ais_traffic.hpp"
#include "support/ais_collector.hpp"
#include "support/example_file.hpp"
#include "support/gpsd_udp.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_dir.hpp"

namespace {

using avk::testing::AisCollector;

TEST(TrafficCli, ScenarioContactsReachGpsdOverUdpWithPositionsAndNames) {
  const auto traffic =
      avk::sim::AisTraffic::parse(avk::testing::example_text("traffic-charles.json"));
  avk::testing::GpsdUdp gpsd;
  avk::testing::TempDir dir("traffic_cli");
  const std::string log = (dir.path() / "traffic.log").string();
  const pid_t pid = avk::testing::spawn_avk(
      {"traffic", "--scenario", std::string(AVK_SOURCE_DIR) + "/examples/traffic-charles.json",
       "--udp", gpsd.udp_source(), "--interval", "1", "--realtime-factor", "10"},
      log);
  ASSERT_GT(pid, 0);
  AisCollector ais(gpsd.port_text());
  std::set<AisCollector::Key> expected;
  for (const auto& c : traffic.contacts()) {
    expected.insert({c.vessel.mmsi, c.vessel.ais_class == avk::sim::AisClass::a ? 1 : 18});
    expected.insert({c.vessel.mmsi, 5});
  }
  const bool all = ais.wait_for([&](const AisCollector& c) { return c.has_all(expected); });
  ais.stop();
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(all) << "received: " << ais.received() << "\ngpsd: " << gpsd.output();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "avk traffic ended badly";
  const auto reports = ais.reports();
  for (const auto& c : traffic.contacts()) {
    EXPECT_EQ(reports.at({c.vessel.mmsi, 5}).name, c.vessel.name);
    // Moving along its track: a speed over ground that is the scenario's.
    const auto& p =
        reports.at({c.vessel.mmsi, c.vessel.ais_class == avk::sim::AisClass::a ? 1 : 18});
    ASSERT_TRUE(p.speed_mps.has_value());
    EXPECT_NEAR(*p.speed_mps, c.speed_mps, 0.06);
  }
}

TEST(TrafficCli, MistakesAreNamed) {
  avk::testing::TempDir dir("traffic_cli_bad");
  const std::string log = (dir.path() / "bad.log").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"traffic", "--udp", "127.0.0.1:1"},
        std::vector<std::string>{"traffic", "--scenario", "x.json"},
        std::vector<std::string>{"traffic", "--scenario", "missing.json", "--udp", "127.0.0.1:1"},
        std::vector<std::string>{"traffic", "--scenario", "x.json", "--udp", "nohostport"}}) {
    const pid_t pid = avk::testing::spawn_avk(args, log);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << args.back();
  }
}

}  // namespace
