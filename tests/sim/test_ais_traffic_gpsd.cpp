// The simulated traffic's AIVDM, decoded by a real gpsd (gpsfake): what the encoder wrote must come
// back within AIS's quantisation (1/10000 minute of position, 0.1 kn, 0.1 degree of course, whole
// degrees of heading), names upper-cased.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "sim/ais_traffic.hpp"
#include "support/ais_collector.hpp"
#include "support/example_file.hpp"
#include "support/gpsfake.hpp"
#include "support/temp_dir.hpp"
#include "support/traffic_log.hpp"
#include "vehicle/nmea.hpp"

namespace {

using avk::testing::AisCollector;

constexpr double kLatLonTol_deg = 0.5 / 600000.0 + 1e-9;
constexpr double kSpeedTol_mps = 0.05 * avk::vehicle::kMetresPerSecondPerKnot + 1e-9;
constexpr double kCourseTol_deg = 0.05 + 1e-9;

double angle_diff_deg(double a, double b) {
  return std::abs(std::remainder(a - b, 360.0));
}

TEST(AisTrafficGpsd, EncodedTrafficDecodesToWhatWasEncoded) {
  const auto traffic =
      avk::sim::AisTraffic::parse(avk::testing::example_text("traffic-charles.json"));
  const double t_s = 47.3;  // mid-leg on the circuits, at an odd time
  avk::testing::TempDir dir("ais_traffic_gpsd");
  dir.write("traffic.aivdm", avk::testing::traffic_log_at(traffic, t_s));

  avk::testing::Gpsfake gpsd(dir.path() / "traffic.aivdm");
  AisCollector ais(gpsd.port_text());
  std::set<AisCollector::Key> expected;
  for (const auto& c : traffic.contacts()) {
    expected.insert({c.vessel.mmsi, c.vessel.ais_class == avk::sim::AisClass::a ? 1 : 18});
    expected.insert({c.vessel.mmsi, 5});
  }
  ASSERT_TRUE(ais.wait_for([&](const AisCollector& c) { return c.has_all(expected); }))
      << "received: " << ais.received() << "\ngpsfake: " << gpsd.output();
  ais.stop();
  const auto reports = ais.reports();

  for (const auto& s : traffic.at(t_s)) {
    SCOPED_TRACE(s.vessel.mmsi);
    const bool class_a = s.vessel.ais_class == avk::sim::AisClass::a;
    const auto& p = reports.at({s.vessel.mmsi, class_a ? 1 : 18});
    ASSERT_TRUE(p.lat_deg && p.lon_deg && p.speed_mps && p.course_deg && p.heading_deg);
    EXPECT_NEAR(*p.lat_deg, s.position.lat_deg, kLatLonTol_deg);
    EXPECT_NEAR(*p.lon_deg, s.position.lon_deg, kLatLonTol_deg);
    EXPECT_NEAR(*p.speed_mps, s.speed_mps, kSpeedTol_mps);
    EXPECT_LE(angle_diff_deg(*p.course_deg, s.course_deg), kCourseTol_deg);
    EXPECT_LE(angle_diff_deg(*p.heading_deg, s.course_deg), 0.5 + 1e-9);
    EXPECT_EQ(p.nav_status, class_a ? std::optional<int>(0) : std::nullopt);
    const auto& st = reports.at({s.vessel.mmsi, 5});
    EXPECT_EQ(st.name, s.vessel.name);  // the example's names are upper case and at most 20 long
  }
  for (const auto& c : traffic.contacts()) {
    const auto& st = reports.at({c.vessel.mmsi, 5});
    EXPECT_EQ(st.ship_type, c.vessel.ship_type) << c.vessel.mmsi;
  }
}

}  // namespace
