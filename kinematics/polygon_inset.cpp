#include "kinematics/polygon_inset.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>

namespace avk::kinematics {

namespace {

Eigen::Vector2d vec(const Point& p) {
  return {p.x_m, p.y_m};
}

double signed_area(const Polyline& poly) {
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& a = poly[i];
    const auto& b = poly[(i + 1) % poly.size()];
    twice += a.x_m * b.y_m - b.x_m * a.y_m;
  }
  return 0.5 * twice;
}

}  // namespace

Polyline inset_polygon(const Polyline& polygon, double distance_m) {
  Polyline poly = polygon;
  // A closing vertex equal to the first adds a zero-length edge with no normal.
  if (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
  const std::size_t n = poly.size();
  if (n < 3) return {};
  const double area = signed_area(poly);
  if (area == 0.0) return {};
  // Counter-clockwise polygons have their interior to the left of each edge.
  const double side = area > 0.0 ? 1.0 : -1.0;
  struct Line {
    Eigen::Vector2d point, direction;
  };
  std::vector<Line> offset;
  offset.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = vec(poly[i]);
    const Eigen::Vector2d d = vec(poly[(i + 1) % n]) - a;
    if (d.norm() == 0.0) continue;
    const Eigen::Vector2d inward = side * Eigen::Vector2d(-d.y(), d.x()).normalized();
    offset.push_back({a + distance_m * inward, d});
  }
  if (offset.size() < 3) return {};
  Polyline out;
  out.reserve(offset.size());
  for (std::size_t i = 0; i < offset.size(); ++i) {
    const Line& prev = offset[(i + offset.size() - 1) % offset.size()];
    const Line& cur = offset[i];
    Eigen::Matrix2d m;
    m << prev.direction, -cur.direction;
    // Collinear consecutive edges: their offsets are one line, and the vertex moves straight in.
    if (std::abs(m.determinant()) < 1e-12 * prev.direction.squaredNorm())
      out.push_back({cur.point.x(), cur.point.y()});
    else {
      const Eigen::Vector2d st = m.colPivHouseholderQr().solve(cur.point - prev.point);
      const Eigen::Vector2d p = prev.point + st.x() * prev.direction;
      out.push_back({p.x(), p.y()});
    }
  }
  // An inset wider than the polygon turns it inside out: an edge runs against its original
  // direction (a square of half width 10 inset by 11 comes back rotated by 180 degrees, its
  // winding unchanged, so the area's sign alone would not tell).
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Eigen::Vector2d e = vec(out[(i + 1) % out.size()]) - vec(out[i]);
    if (e.dot(offset[i].direction) <= 0.0) return {};
  }
  return out;
}

}  // namespace avk::kinematics
