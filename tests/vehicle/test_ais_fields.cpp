// AIS's scaled fields to the project's units, and every "not available" value to nullopt.
#include <gtest/gtest.h>

#include "vehicle/ais_fields.hpp"
#include "vehicle/nmea.hpp"

namespace {

using namespace avk::vehicle;

TEST(AisFields, PositionsAreInTenThousandthsOfAMinute) {
  EXPECT_DOUBLE_EQ(*ais_lat_deg(29028980), 29028980 / 600000.0);
  EXPECT_NEAR(*ais_lat_deg(29028980), 48.38163333, 1e-8);
  EXPECT_NEAR(*ais_lon_deg(-74037230), -123.39538333, 1e-8);
  EXPECT_DOUBLE_EQ(*ais_lat_deg(-90 * 600000), -90.0);
  EXPECT_DOUBLE_EQ(*ais_lon_deg(-180 * 600000), -180.0);
  EXPECT_FALSE(ais_lat_deg(kAisLatNotAvailable));  // 91 degrees
  EXPECT_FALSE(ais_lon_deg(kAisLonNotAvailable));  // 181 degrees
  EXPECT_FALSE(ais_lat_deg(-90 * 600000 - 1));
  EXPECT_FALSE(ais_lon_deg(180 * 600000 + 5));
}

TEST(AisFields, SpeedIsTenthsOfAKnot) {
  EXPECT_DOUBLE_EQ(*ais_speed_mps(0), 0.0);
  EXPECT_NEAR(*ais_speed_mps(123), 12.3 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(*ais_speed_mps(kAisSpeedMax), 102.2 * kMetresPerSecondPerKnot, 1e-12);
  EXPECT_FALSE(ais_speed_mps(kAisSpeedNotAvailable));
}

TEST(AisFields, CourseHeadingStatusAndShipType) {
  EXPECT_DOUBLE_EQ(*ais_course_deg(934), 93.4);
  EXPECT_DOUBLE_EQ(*ais_course_deg(3599), 359.9);
  EXPECT_FALSE(ais_course_deg(kAisCourseNotAvailable));
  EXPECT_FALSE(ais_course_deg(4095));
  EXPECT_DOUBLE_EQ(*ais_heading_deg(359), 359.0);
  EXPECT_FALSE(ais_heading_deg(kAisHeadingNotAvailable));
  EXPECT_FALSE(ais_heading_deg(360));
  EXPECT_EQ(*ais_nav_status(5), 5);
  EXPECT_FALSE(ais_nav_status(kAisNavStatusNotDefined));
  EXPECT_EQ(*ais_ship_type(70), 70);
  EXPECT_FALSE(ais_ship_type(kAisShipTypeNotAvailable));
  EXPECT_FALSE(ais_ship_type(200));
}

TEST(AisFields, TextLosesItsPadding) {
  EXPECT_EQ(*ais_text("EVER DIADEM@@@@@@@@@"), "EVER DIADEM");
  EXPECT_EQ(*ais_text("3FOF8  "), "3FOF8");
  EXPECT_EQ(*ais_text("A B"), "A B");
  EXPECT_FALSE(ais_text(""));
  EXPECT_FALSE(ais_text("@@@@   @@"));
}

}  // namespace
