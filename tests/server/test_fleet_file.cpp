// `avk serve --vehicles FILE`: the fleet document read into the vehicles' options, and every
// mistake named by the file and the JSON pointer of the field.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/vehicle_source.hpp"
#include "server/cli/fleet_file.hpp"

namespace {

using avk::server::parse_fleet_file;

std::string example_fleet_path() {
  return std::string(AVK_SOURCE_DIR) + "/examples/fleet.json";
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the error parsing text as the fleet file "fleet.json" gives.
std::string error_of(const std::string& text) {
  try {
    parse_fleet_file("fleet.json", text, 1.0, 0.0, std::nullopt);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FleetFile, TheExampleIsThreeSimulatedVehiclesEachWithItsOwnStartAndSeed) {
  const auto fleet =
      parse_fleet_file(example_fleet_path(), read(example_fleet_path()), 10.0, 123.0, std::nullopt);
  ASSERT_EQ(fleet.size(), 3u);
  const std::vector<std::string> ids = {"alpha", "bravo", "charlie"};
  for (std::size_t i = 0; i < fleet.size(); ++i) {
    EXPECT_EQ(avk::app::planned_vehicle_info(fleet[i]).id, ids[i]);
    EXPECT_EQ(fleet[i].setup.scheduler.seed, i + 1);
    EXPECT_EQ(fleet[i].realtime_factor, 10.0);
    EXPECT_EQ(fleet[i].start_clock_s, 123.0);
    // The sim config named relative to the fleet file: sim-choppy's current is read.
    EXPECT_GT(fleet[i].setup.vehicle.environment.current.speed_mps, 0.0);
  }
  EXPECT_EQ(fleet[1].start.x_m, 300.0);
  EXPECT_EQ(fleet[2].start.x_m, -300.0);
}

TEST(FleetFile, AnM200IsNamedByItsAddress) {
  const auto fleet = parse_fleet_file(
      "f.json", R"({"vehicles":[{"id":"lab","m200":"127.0.0.1:29500","pid":"m200_in_water"}]})",
      1.0, 0.0, std::nullopt);
  ASSERT_EQ(fleet.size(), 1u);
  EXPECT_EQ(avk::app::kind_of(fleet[0]), avk::vehicle::VehicleKind::m200);
  ASSERT_TRUE(fleet[0].m200.has_value());
  EXPECT_EQ(fleet[0].m200->config.id, "lab");
}

TEST(FleetFile, MistakesNameTheFileAndTheField) {
  EXPECT_NE(error_of("{").find("fleet.json: not JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[]})").find("fleet.json: /vehicles:"), std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a"}],"extra":1})").find("/extra"), std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"vehicle":"usim"}]})").find("/vehicles/0/id"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a"},{"id":"a"}]})").find("/vehicles/1/id"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a/b"}]})").find("/vehicles/0/id"), std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a","start":{"heading_deg":360}}]})")
                .find("/vehicles/0/start/heading_deg"),
            std::string::npos);
  EXPECT_NE(
      error_of(R"({"vehicles":[{"id":"a","start":{"x_m":"east"}}]})").find("/vehicles/0/start/x_m"),
      std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a","speed":1}]})").find("/vehicles/0/speed"),
            std::string::npos);
  EXPECT_NE(
      error_of(R"({"vehicles":[{"id":"a","vehicle":"zeppelin"}]})").find("/vehicles/0/vehicle"),
      std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"a","sim_config":"missing.json"}]})")
                .find("/vehicles/0/sim_config"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"vehicles":[{"id":"m","m200":"boat:99999"}]})").find("/vehicles/0/m200"),
            std::string::npos);
}

}  // namespace
