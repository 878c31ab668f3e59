#pragma once
// OpRegion and OpReg Container (thesis §4.4.2): outside the region the vehicle is halted; inside
// the buffer band along the boundary it heads for the interior until it is out of the band.

#include "mission/mission_config.hpp"

namespace avk::mission {

enum class RegionZone { interior, buffer, outside };
const char* to_string(RegionZone z);

class Container {
 public:
  explicit Container(OperatingRegion region);

  RegionZone zone(kinematics::Point p) const;
  // How far p is inside the interior (past the buffer's inner edge); negative in the buffer.
  double depth_in_interior_m(kinematics::Point p) const;
  // How far a straight run from p on course_deg stays in the interior, in 1 m steps, up to
  // limit_m (returned when it never leaves it).
  double run_before_buffer_m(kinematics::Point p, double course_deg, double limit_m) const;
  // Heading (deg clockwise from north) from p towards the region's interior point.
  double heading_to_interior_deg(kinematics::Point p) const;
  kinematics::Point interior_point() const { return interior_; }
  const OperatingRegion& region() const { return region_; }

 private:
  OperatingRegion region_;
  kinematics::Point
      interior_;  // the area centroid, or the return point when the centroid lies outside
};

}  // namespace avk::mission
