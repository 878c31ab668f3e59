// The AIS traffic table: merging static data with positions, the local grid, aging on an injected
// clock, and reports that must not make contacts.
#include <gtest/gtest.h>

#include <cmath>

#include "app/ais_contacts.hpp"

namespace {

using avk::app::AisContacts;
using avk::app::AisContactView;
using avk::vehicle::AisReport;

constexpr double kDatumLat = 42.358456;
constexpr double kDatumLon = -71.087589;

struct Table {
  double now_s = 1000.0;
  AisContacts contacts{{kDatumLat, kDatumLon}, [this] { return now_s; }};
};

AisReport position(std::uint32_t mmsi, double lat, double lon, double received_s,
                   std::optional<double> speed_mps = 2.0) {
  AisReport r;
  r.mmsi = mmsi;
  r.message_type = 1;
  r.lat_deg = lat;
  r.lon_deg = lon;
  r.speed_mps = speed_mps;
  r.course_deg = 90.0;
  r.heading_deg = 92.0;
  r.position_accuracy_high = true;
  r.received_s = received_s;
  return r;
}

AisReport name(std::uint32_t mmsi, const std::string& n, double received_s) {
  AisReport r;
  r.mmsi = mmsi;
  r.message_type = 5;
  r.name = n;
  r.callsign = "WDA1234";
  r.ship_type = 52;
  r.received_s = received_s;
  return r;
}

TEST(AisContacts, AContactAtTheDatumIsAtTheOriginAndNorthIsPlusY) {
  Table t;
  t.contacts.update(position(1, kDatumLat, kDatumLon, t.now_s));
  t.contacts.update(position(2, kDatumLat + 0.001, kDatumLon, t.now_s));
  t.contacts.update(position(3, kDatumLat, kDatumLon + 0.001, t.now_s));
  const auto s = t.contacts.snapshot();
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s[0].x_m, 0.0, 1e-6);
  EXPECT_NEAR(s[0].y_m, 0.0, 1e-6);
  // 0.001 degree of latitude is about 111 m; of longitude, that times cos(latitude).
  EXPECT_NEAR(s[1].x_m, 0.0, 0.01);
  EXPECT_NEAR(s[1].y_m, 111.1, 0.5);
  EXPECT_NEAR(s[2].x_m, 111.3 * std::cos(kDatumLat * M_PI / 180.0), 0.5);
  EXPECT_NEAR(s[2].y_m, 0.0, 0.01);
  EXPECT_EQ(s[1].mmsi, 2u);
  EXPECT_DOUBLE_EQ(s[1].lat_deg, kDatumLat + 0.001);
  EXPECT_EQ(s[1].course_deg, 90.0);
  EXPECT_EQ(s[1].heading_deg, 92.0);
  EXPECT_EQ(s[1].speed_mps, 2.0);
}

TEST(AisContacts, NamesMergeWithPositionsInEitherOrder) {
  Table t;
  t.contacts.update(name(7, "HARBOR TUG", t.now_s));  // static data first: no contact yet
  EXPECT_TRUE(t.contacts.snapshot().empty());
  t.now_s += 20;
  t.contacts.update(position(7, kDatumLat, kDatumLon, t.now_s));
  t.contacts.update(position(8, kDatumLat, kDatumLon, t.now_s));
  t.now_s += 5;
  t.contacts.update(name(8, "LAUNCH", t.now_s));  // position first
  const auto s = t.contacts.snapshot();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].name, "HARBOR TUG");
  EXPECT_EQ(s[0].callsign, "WDA1234");
  EXPECT_EQ(s[0].ship_type, 52);
  EXPECT_EQ(s[1].name, "LAUNCH");
  EXPECT_DOUBLE_EQ(s[1].age_s, 5.0);
  // A later position keeps the name.
  t.contacts.update(position(7, kDatumLat + 0.0001, kDatumLon, t.now_s));
  EXPECT_EQ(t.contacts.snapshot()[0].name, "HARBOR TUG");
}

TEST(AisContacts, MovingContactsAgeOutAfterThreeMinutesSlowOnesLater) {
  Table t;
  t.contacts.update(position(1, kDatumLat, kDatumLon, t.now_s, 5.0));           // moving
  t.contacts.update(position(2, kDatumLat, kDatumLon, t.now_s, 0.2));           // nearly stopped
  t.contacts.update(position(3, kDatumLat, kDatumLon, t.now_s, std::nullopt));  // speed unknown
  t.now_s += 180.0;
  EXPECT_EQ(t.contacts.snapshot().size(), 3u) << "at exactly the age, still there";
  EXPECT_DOUBLE_EQ(t.contacts.snapshot()[0].age_s, 180.0);
  t.now_s += 0.5;
  auto s = t.contacts.snapshot();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].mmsi, 2u);
  EXPECT_EQ(s[1].mmsi, 3u);
  t.now_s = 1000.0 + 600.5;
  EXPECT_TRUE(t.contacts.snapshot().empty());
  // An update prunes what has aged out.
  t.contacts.update(position(4, kDatumLat, kDatumLon, t.now_s));
  EXPECT_EQ(t.contacts.size(), 1u);
}

TEST(AisContacts, AgingIsConfigurable) {
  double now_s = 0.0;
  AisContacts c({kDatumLat, kDatumLon}, [&] { return now_s; },
                {.max_age_s = 10.0, .slow_max_age_s = 20.0});
  c.update(position(1, kDatumLat, kDatumLon, 0.0, 5.0));
  now_s = 10.5;
  EXPECT_TRUE(c.snapshot().empty());
}

TEST(AisContacts, ReportsWithoutPositionOrDataMakeNoContact) {
  Table t;
  AisReport no_position = position(1, 0, 0, t.now_s);
  no_position.lat_deg.reset();
  no_position.lon_deg.reset();
  t.contacts.update(no_position);
  AisReport no_mmsi = position(0, kDatumLat, kDatumLon, t.now_s);
  t.contacts.update(no_mmsi);
  AisReport only_lat = position(2, kDatumLat, kDatumLon, t.now_s);
  only_lat.lon_deg.reset();
  t.contacts.update(only_lat);
  EXPECT_TRUE(t.contacts.snapshot().empty());
  EXPECT_EQ(t.contacts.size(), 0u);
}

TEST(AisContacts, ToKinematicsContactDeadReckonsAndSpreadsByAccuracy) {
  AisContactView v;
  v.x_m = 100.0;
  v.y_m = -50.0;
  v.speed_mps = 2.0;
  v.course_deg = 90.0;
  v.age_s = 10.0;
  v.position_accuracy_high = true;
  auto k = avk::app::to_kinematics_contact(v);
  ASSERT_TRUE(k);
  EXPECT_NEAR(k->x_m, 120.0, 1e-9);  // 10 s at 2 m/s east
  EXPECT_NEAR(k->y_m, -50.0, 1e-9);
  EXPECT_DOUBLE_EQ(k->course_deg, 90.0);
  EXPECT_DOUBLE_EQ(k->speed_mps, 2.0);
  EXPECT_DOUBLE_EQ(k->position_sd_m, 10.0);
  v.position_accuracy_high = false;
  EXPECT_DOUBLE_EQ(avk::app::to_kinematics_contact(v)->position_sd_m, 100.0);
  // No course: not moved, and any direction.
  v.course_deg.reset();
  k = avk::app::to_kinematics_contact(v);
  ASSERT_TRUE(k);
  EXPECT_DOUBLE_EQ(k->x_m, 100.0);
  EXPECT_DOUBLE_EQ(k->course_sd_deg, 180.0);
  // No speed: no contact to predict.
  v.speed_mps.reset();
  EXPECT_FALSE(avk::app::to_kinematics_contact(v));
}

}  // namespace
