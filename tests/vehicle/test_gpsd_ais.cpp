// The gpsd AIS client against a real gpsd fed by gpsfake: published sample sentences
// (tests/data/ais_samples.aivdm) must arrive with their published decodes; malformed input must
// not stop it; it must find gpsd when gpsd starts after it, and again after gpsd went away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/ais_collector.hpp"
#include "support/gpsfake.hpp"
#include "support/temp_dir.hpp"
#include "vehicle/nmea.hpp"

namespace {

using avk::testing::AisCollector;
using avk::testing::Gpsfake;
using avk::vehicle::AisReport;
using avk::vehicle::kMetresPerSecondPerKnot;

const std::string kSamples = std::string(AVK_SOURCE_DIR) + "/tests/data/ais_samples.aivdm";

// The published decodes give positions to 1e-8 degree or better; AIS's unit is 1/600000.
constexpr double kLatLonTol_deg = 1e-7;

struct ExpectedPosition {
  std::uint32_t mmsi;
  int type;
  double lat_deg;
  double lon_deg;
  double speed_kn;
  bool accuracy_high;
  double course_deg;
  std::optional<double> heading_deg;
  std::optional<int> nav_status;
};

void expect_position(const AisReport& r, const ExpectedPosition& e) {
  SCOPED_TRACE(e.mmsi);
  ASSERT_TRUE(r.lat_deg && r.lon_deg);
  EXPECT_NEAR(*r.lat_deg, e.lat_deg, kLatLonTol_deg);
  EXPECT_NEAR(*r.lon_deg, e.lon_deg, kLatLonTol_deg);
  ASSERT_TRUE(r.speed_mps);
  EXPECT_NEAR(*r.speed_mps, e.speed_kn * kMetresPerSecondPerKnot, 1e-9);
  EXPECT_EQ(r.position_accuracy_high, e.accuracy_high);
  ASSERT_TRUE(r.course_deg);
  EXPECT_NEAR(*r.course_deg, e.course_deg, 1e-9);
  EXPECT_EQ(r.heading_deg, e.heading_deg);
  EXPECT_EQ(r.nav_status, e.nav_status);
}

TEST(GpsdAis, SampleSentencesArriveWithTheirPublishedDecodes) {
  Gpsfake gpsd(kSamples);
  AisCollector ais(gpsd.port_text());
  const std::set<AisCollector::Key> expected = {{371798000, 1},  {440348000, 1}, {356302000, 2},
                                                {563808000, 3},  {351759000, 5}, {338087471, 18},
                                                {367059850, 19}, {271041815, 24}};
  ASSERT_TRUE(ais.wait_for([&](const AisCollector& c) { return c.has_all(expected); }))
      << "received: " << ais.received() << "\ngpsfake: " << gpsd.output();
  ais.stop();
  const auto r = ais.reports();

  expect_position(r.at({371798000, 1}),
                  {371798000, 1, 48.38163333333, -123.395383333, 12.3, true, 224.0, 215.0, 0});
  expect_position(r.at({440348000, 1}),
                  {440348000, 1, 43.08015, -70.7582, 0.0, false, 93.4, std::nullopt, 0});
  expect_position(r.at({356302000, 2}),
                  {356302000, 2, 40.39235833333, -71.62614333333, 13.9, false, 87.7, 91.0, 0});
  expect_position(r.at({563808000, 3}),
                  {563808000, 3, 36.91, -76.32753333333, 0.0, true, 252.0, 352.0, 5});
  expect_position(r.at({338087471, 18}), {338087471, 18, 40.68454, -74.07213166667, 0.1, false,
                                          79.6, std::nullopt, std::nullopt});
  expect_position(r.at({367059850, 19}), {367059850, 19, 29.543695, -88.8103916667, 8.7, false,
                                          335.9, std::nullopt, std::nullopt});
  // Class A positions carry no name, static data no position.
  EXPECT_FALSE(r.at({371798000, 1}).name);

  const AisReport& t5 = r.at({351759000, 5});
  EXPECT_EQ(t5.name, "EVER DIADEM");
  EXPECT_EQ(t5.callsign, "3FOF8");
  EXPECT_EQ(t5.ship_type, 70);
  EXPECT_FALSE(t5.lat_deg);
  EXPECT_FALSE(t5.speed_mps);

  EXPECT_EQ(r.at({367059850, 19}).name, "CAPT.J.RIMES");
  EXPECT_EQ(r.at({367059850, 19}).ship_type, 70);

  const AisReport& t24 = r.at({271041815, 24});
  EXPECT_EQ(t24.name, "PROGUY");
  EXPECT_EQ(t24.callsign, "TC6163");
  EXPECT_EQ(t24.ship_type, 60);
  EXPECT_FALSE(t24.lat_deg);

  // The link came up once and stayed up while gpsd ran.
  ASSERT_FALSE(ais.links().empty());
  EXPECT_TRUE(ais.links().front());
}

// `!body*hh` with the right checksum, so that gpsd has to look inside.
std::string aivdm(const std::string& body) {
  char sum[8];
  std::snprintf(sum, sizeof sum, "*%02X\n", avk::vehicle::nmea_checksum(body));
  return "!" + body + sum;
}

TEST(GpsdAis, MalformedSentencesAreDroppedAndTheStreamGoesOn) {
  avk::testing::TempDir dir("gpsd_ais_malformed");
  // A bad checksum, then well-framed sentences with bad insides: a truncated payload, a fragment
  // without its first part, characters outside the six-bit alphabet, a payload far too long, a
  // fill count out of range; binary junk; and last one good sentence.
  std::string junk = "!AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,0*4B\n";
  junk += aivdm("AIVDM,1,1,,A,15RTgt0P,0");
  junk += aivdm("AIVDM,2,2,7,A,88888888880,2");
  junk += aivdm("AIVDM,1,1,,A,1~~~~~~~~~~~~~~~~~~~~~~~~~~~,0");
  junk += aivdm("AIVDM,1,1,,A," + std::string(300, '1') + ",0");
  junk += aivdm("AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,9");
  junk += "\x01\x02\xff\xfe garbage\n";
  junk += "!AIVDM,1,1,,A,16SteH0P00Jt63hHaa6SagvJ087r,0*42\n";
  dir.write("junk.aivdm", junk);
  Gpsfake gpsd(dir.path() / "junk.aivdm");
  AisCollector ais(gpsd.port_text());
  ASSERT_TRUE(ais.wait_for([](const AisCollector& c) {
    return c.has_all({{440348000, 1}});
  })) << "received: "
      << ais.received() << "\ngpsfake: " << gpsd.output();
  ais.stop();
  // The bad checksum's sentence (371798000) never came through.
  for (const auto& r : ais.all())
    EXPECT_NE(r.mmsi, 371798000u) << "type " << r.message_type;
}

TEST(GpsdAis, FindsGpsdWhenItStartsLaterAndAgainAfterItWentAway) {
  const int port = avk::testing::free_loopback_port();
  AisCollector ais(std::to_string(port));
  // No gpsd yet: the client retries and reports no link.
  EXPECT_TRUE(ais.links().empty());
  auto one_up = [](const AisCollector& c) {
    return !c.links().empty() && c.links().back() && !c.all().empty();
  };
  {
    Gpsfake gpsd(kSamples, port);
    ASSERT_TRUE(ais.wait_for(one_up)) << "gpsfake: " << gpsd.output();
  }
  // gpsd is gone: the link goes down.
  ASSERT_TRUE(ais.wait_for([](const AisCollector& c) { return !c.links().back(); }));
  const std::size_t before = ais.all().size();
  Gpsfake again(kSamples, port);
  ASSERT_TRUE(ais.wait_for([&](const AisCollector& c) {
    return c.links().size() >= 3 && c.links().back() && c.all().size() > before;
  })) << "links: "
      << ais.links().size() << "\ngpsfake: " << again.output();
  ais.stop();
  EXPECT_EQ(ais.links(), (std::vector<bool>{true, false, true, false}));
}

}  // namespace
