// The simulated AIS traffic: the scenario file, positions at time t, and the AIVDM encoder's
// framing; tests/sim/test_ais_traffic_gpsd.cpp decodes what it sends with a real gpsd.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/ais_traffic.hpp"
#include "sim/aivdm_encoder.hpp"
#include "support/example_file.hpp"
#include "vehicle/nmea.hpp"

namespace {

using avk::sim::AisTraffic;
using avk::sim::TrafficScenarioError;

// The field named by the error of a scenario that does not parse.
std::string bad_field(const std::string& json) {
  try {
    AisTraffic::parse(json);
  } catch (const TrafficScenarioError& e) {
    EXPECT_FALSE(e.errors().empty());
    EXPECT_NE(std::string(e.what()).find(e.errors().front().field), std::string::npos);
    return e.errors().front().field;
  }
  return "(parsed)";
}

std::string scenario(const std::string& contact) {
  return R"({"datum": {"lat_deg": 42.358456, "lon_deg": -71.087589}, "contacts": [)" + contact +
         "]}";
}

TEST(AisTraffic, TheExampleScenarioParsesNearTheSimulatorsDatum) {
  const AisTraffic t = AisTraffic::parse(avk::testing::example_text("traffic-charles.json"));
  EXPECT_DOUBLE_EQ(t.datum().lat_deg, 42.358456);
  EXPECT_DOUBLE_EQ(t.datum().lon_deg, -71.087589);
  ASSERT_GE(t.contacts().size(), 3u);
  ASSERT_LE(t.contacts().size(), 5u);
  for (const auto& s : t.at(120.0)) {
    EXPECT_LT(std::hypot(s.x_m, s.y_m), 2000.0) << s.vessel.mmsi;
    EXPECT_FALSE(s.vessel.name.empty());
  }
}

TEST(AisTraffic, StraightTracksRunAtTheirCourseAndSpeed) {
  const AisTraffic t = AisTraffic::parse(
      scenario(R"({"mmsi": 1, "speed_mps": 2.0, "start": [10, 20], "course_deg": 90})"));
  auto s = t.at(0.0).at(0);
  EXPECT_DOUBLE_EQ(s.x_m, 10.0);
  EXPECT_DOUBLE_EQ(s.y_m, 20.0);
  s = t.at(30.0).at(0);
  EXPECT_NEAR(s.x_m, 70.0, 1e-9);  // east
  EXPECT_NEAR(s.y_m, 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.course_deg, 90.0);
  EXPECT_DOUBLE_EQ(s.speed_mps, 2.0);
  // The position on the ellipsoid is the grid point's.
  EXPECT_GT(s.position.lon_deg, -71.087589);
  EXPECT_NEAR(s.position.lat_deg, 42.358456 + 20.0 / 111070.0, 2e-6);
}

TEST(AisTraffic, WaypointCircuitsCloseOnThemselves) {
  // A 100 m square: north, east, south, west; 400 m round.
  const AisTraffic t = AisTraffic::parse(
      scenario(R"({"mmsi": 2, "speed_mps": 10, "waypoints": [[0,0],[0,100],[100,100],[100,0]]})"));
  auto s = t.at(5.0).at(0);  // 50 m up the first leg
  EXPECT_NEAR(s.x_m, 0.0, 1e-9);
  EXPECT_NEAR(s.y_m, 50.0, 1e-9);
  EXPECT_NEAR(s.course_deg, 0.0, 1e-9);
  s = t.at(15.0).at(0);  // 50 m along the second
  EXPECT_NEAR(s.x_m, 50.0, 1e-9);
  EXPECT_NEAR(s.y_m, 100.0, 1e-9);
  EXPECT_NEAR(s.course_deg, 90.0, 1e-9);
  s = t.at(35.0).at(0);  // the closing leg, west
  EXPECT_NEAR(s.x_m, 50.0, 1e-9);
  EXPECT_NEAR(s.y_m, 0.0, 1e-9);
  EXPECT_NEAR(s.course_deg, 270.0, 1e-9);
  s = t.at(45.0).at(0);  // round again
  EXPECT_NEAR(s.x_m, 0.0, 1e-9);
  EXPECT_NEAR(s.y_m, 50.0, 1e-9);
}

TEST(AisTraffic, BadFieldsAreNamed) {
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 0, "speed_mps": 1, "start": [0,0], "course_deg": 0})")),
            "/contacts/0/mmsi");
  EXPECT_EQ(bad_field(scenario(R"({"speed_mps": 1, "start": [0,0], "course_deg": 0})")),
            "/contacts/0/mmsi");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": -1, "start": [0,0], "course_deg": 0})")),
            "/contacts/0/speed_mps");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "start": [0], "course_deg": 0})")),
            "/contacts/0/start");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "start": [0,0]})")),
            "/contacts/0/course_deg");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "waypoints": [[0,0]]})")),
            "/contacts/0/waypoints");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "waypoints": [[0,0],[1,"x"]]})")),
            "/contacts/0/waypoints/1");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "start": [0,0], "course_deg": 0,
                                   "class": "C"})")),
            "/contacts/0/class");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "start": [0,0], "course_deg": 0,
                                   "name": "A NAME LONGER THAN TWENTY"})")),
            "/contacts/0/name");
  EXPECT_EQ(bad_field(scenario(R"({"mmsi": 5, "speed_mps": 1, "start": [0,0], "course_deg": 0,
                                   "speed_kn": 3})")),
            "/contacts/0/speed_kn");
  EXPECT_EQ(bad_field(R"({"contacts": []})"), "/datum");
  EXPECT_EQ(bad_field(R"({"datum": {"lat_deg": 95, "lon_deg": 0}, "contacts": [{}]})"),
            "/datum/lat_deg");
  EXPECT_EQ(bad_field(R"({"datum": )"), "json");
}

// ---- The encoder's framing --------------------------------------------------------------------

void expect_framed(const std::string& line) {
  ASSERT_GE(line.size(), 20u);
  EXPECT_EQ(line.substr(0, 7), "!AIVDM,");
  EXPECT_EQ(line.substr(line.size() - 2), "\r\n");
  const std::size_t star = line.rfind('*');
  ASSERT_NE(star, std::string::npos);
  EXPECT_EQ(std::stoi(line.substr(star + 1, 2), nullptr, 16),
            avk::vehicle::nmea_checksum(std::string_view(line).substr(1, star - 1)))
      << line;
  EXPECT_LE(line.size(), 82u) << "NMEA's longest sentence";
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line.substr(0, line.rfind('*'))) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

TEST(AivdmEncoder, PositionReportsAreOneSentenceOf168Bits) {
  avk::sim::AisPositionMessage m;
  m.mmsi = 367000101;
  m.lat_deg = 42.36;
  m.lon_deg = -71.08;
  m.speed_mps = 2.5;
  m.course_deg = 75.0;
  for (const auto& lines :
       {avk::sim::encode_class_a_position(m), avk::sim::encode_class_b_position(m)}) {
    ASSERT_EQ(lines.size(), 1u);
    expect_framed(lines[0]);
    const auto f = fields(lines[0]);
    ASSERT_EQ(f.size(), 7u);
    EXPECT_EQ(f[1], "1");
    EXPECT_EQ(f[2], "1");
    EXPECT_EQ(f[5].size(), 28u);  // 168 bits
    EXPECT_EQ(f[6], "0");         // no fill
  }
  EXPECT_EQ(fields(avk::sim::encode_class_a_position(m)[0])[5][0], '1');  // message type 1
  EXPECT_EQ(fields(avk::sim::encode_class_b_position(m)[0])[5][0], 'B');  // 18
}

TEST(AivdmEncoder, StaticDataTakesTwoSentencesWithOneSequenceId) {
  avk::sim::AisStaticMessage m;
  m.mmsi = 367000102;
  m.name = "Duck Tour 7";
  const auto lines = avk::sim::encode_static_voyage(m, 3);
  ASSERT_EQ(lines.size(), 2u);
  const auto a = fields(lines[0]);
  const auto b = fields(lines[1]);
  for (const auto& l : lines)
    expect_framed(l);
  EXPECT_EQ(a[1], "2");
  EXPECT_EQ(a[2], "1");
  EXPECT_EQ(b[2], "2");
  EXPECT_EQ(a[3], "3");
  EXPECT_EQ(b[3], "3");
  // 424 bits: 70 characters and 4 bits, padded with 2 fill bits to 71.
  EXPECT_EQ(a[5].size() + b[5].size(), 71u);
  EXPECT_EQ(a[6], "0");
  EXPECT_EQ(b[6], "2");
  EXPECT_EQ(a[5][0], '5');
}

TEST(AivdmEncoder, ArmouringSkipsTheEightCharactersAfterW) {
  // Six-bit values 0..39 are '0'..'W', 40..63 are '`'..'w'.
  EXPECT_EQ(avk::sim::aivdm_sentences("000000100111101000111111", 0, 'A')[0].substr(14, 4), "0W`w");
}

TEST(AivdmEncoder, ValuesItCannotSendThrow) {
  avk::sim::AisPositionMessage m;
  m.mmsi = 0;
  EXPECT_THROW(avk::sim::encode_class_a_position(m), std::invalid_argument);
  m.mmsi = 1;
  m.lat_deg = 91.0;
  EXPECT_THROW(avk::sim::encode_class_a_position(m), std::invalid_argument);
  m.lat_deg = 0.0;
  m.speed_mps = std::nan("");
  EXPECT_THROW(avk::sim::encode_class_a_position(m), std::invalid_argument);
}

}  // namespace
