#include <gtest/gtest.h>

#include "mission/container.hpp"

using namespace avk::mission;

namespace {
OperatingRegion square() {
  OperatingRegion r;
  r.polygon = {{-50, -50}, {50, -50}, {50, 50}, {-50, 50}};
  r.buffer_m = 10;
  r.return_point = {0, -40};
  return r;
}
}  // namespace

TEST(Container, ZonesAndHeadingInward) {
  const Container c(square());
  EXPECT_EQ(c.zone({0, 0}), RegionZone::interior);
  EXPECT_EQ(c.zone({45, 0}), RegionZone::buffer);
  EXPECT_EQ(c.zone({0, -49}), RegionZone::buffer);
  EXPECT_EQ(c.zone({60, 0}), RegionZone::outside);
  EXPECT_NEAR(c.heading_to_interior_deg({45, 0}), 270.0, 1e-9);  // west, back inside
  EXPECT_NEAR(c.heading_to_interior_deg({0, -45}), 0.0, 1e-9);
  EXPECT_NEAR(c.interior_point().x_m, 0.0, 1e-9);
}

TEST(Container, ConcaveRegionFallsBackToTheReturnPoint) {
  OperatingRegion r;
  // A U shape whose centroid (in the notch) is outside the region.
  r.polygon = {{0, 0}, {100, 0}, {100, 100}, {70, 100}, {70, 20}, {30, 20}, {30, 100}, {0, 100}};
  r.buffer_m = 5;
  r.return_point = {15, 50};
  const Container c(r);
  EXPECT_EQ(c.zone(c.interior_point()), RegionZone::interior);
  EXPECT_DOUBLE_EQ(c.interior_point().x_m, 15.0);
}

// The straight run before the buffer (the interior is |x|, |y| <= 40): the same on the four
// symmetric courses, longer on the diagonal, capped at the limit, and none from inside the buffer.
TEST(Container, TheRunBeforeTheBufferFollowsTheCourse) {
  const Container c(square());
  for (const double course : {0.0, 90.0, 180.0, 270.0})
    EXPECT_DOUBLE_EQ(c.run_before_buffer_m({0, 0}, course, 100.0), 40.0) << course;
  EXPECT_DOUBLE_EQ(c.run_before_buffer_m({0, 0}, 45.0, 100.0), 56.0);   // 40 √2 = 56.6
  EXPECT_DOUBLE_EQ(c.run_before_buffer_m({30, 0}, 90.0, 100.0), 10.0);  // east, 10 m to go
  EXPECT_DOUBLE_EQ(c.run_before_buffer_m({30, 0}, 270.0, 100.0), 70.0);
  EXPECT_DOUBLE_EQ(c.run_before_buffer_m({0, 0}, 0.0, 25.0), 25.0);
  EXPECT_DOUBLE_EQ(c.run_before_buffer_m({45, 0}, 90.0, 100.0), 0.0);
}
