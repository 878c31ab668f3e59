#include "mission/container.hpp"

#include "kinematics/angles.hpp"

namespace avk::mission {

const char* to_string(RegionZone z) {
  switch (z) {
    case RegionZone::interior:
      return "interior";
    case RegionZone::buffer:
      return "buffer";
    case RegionZone::outside:
      return "outside";
  }
  return "?";
}

namespace {
kinematics::Point area_centroid(const kinematics::Polyline& poly) {
  double a = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % n];
    const double c = p.x_m * q.y_m - q.x_m * p.y_m;
    a += c;
    cx += (p.x_m + q.x_m) * c;
    cy += (p.y_m + q.y_m) * c;
  }
  return {cx / (3.0 * a), cy / (3.0 * a)};
}
}  // namespace

Container::Container(OperatingRegion region) : region_(std::move(region)) {
  interior_ = area_centroid(region_.polygon);
  // A concave region's centroid can lie outside it; the validated return point never does.
  if (!point_in_polygon(interior_, region_.polygon) ||
      distance_to_boundary_m(interior_, region_.polygon) <= region_.buffer_m) {
    interior_ = region_.return_point;
  }
}

RegionZone Container::zone(kinematics::Point p) const {
  if (!point_in_polygon(p, region_.polygon)) return RegionZone::outside;
  return distance_to_boundary_m(p, region_.polygon) < region_.buffer_m ? RegionZone::buffer
                                                                       : RegionZone::interior;
}

double Container::depth_in_interior_m(kinematics::Point p) const {
  return distance_to_boundary_m(p, region_.polygon) - region_.buffer_m;
}

double Container::run_before_buffer_m(kinematics::Point p, double course_deg,
                                      double limit_m) const {
  constexpr double kStep_m = 1.0;
  const kinematics::Point step = kinematics::rotate_by_heading({0.0, kStep_m}, course_deg);
  for (double d = kStep_m; d <= limit_m; d += kStep_m) {
    const double k = d / kStep_m;
    if (zone({p.x_m + k * step.x_m, p.y_m + k * step.y_m}) != RegionZone::interior)
      return d - kStep_m;
  }
  return limit_m;
}

double Container::heading_to_interior_deg(kinematics::Point p) const {
  return kinematics::heading_of_deg(interior_.x_m - p.x_m, interior_.y_m - p.y_m);
}

}  // namespace avk::mission
