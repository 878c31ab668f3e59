#include "kinematics/position_band.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace avk::kinematics {

namespace {

// The unit direction of the segment a -> b, or none for a segment without length.
bool unit_of(const TimedPoint& a, const TimedPoint& b, Point& out) {
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
  const double n = std::hypot(dx, dy);
  if (!(n > 1e-9)) return false;
  out = {dx / n, dy / n};
  return true;
}

}  // namespace

std::vector<Covariance2> position_band(const TimedPath& path, const std::vector<double>& along_sd_m,
                                       const std::vector<double>& cross_sd_m,
                                       std::size_t turn_points, const BandSources& sources) {
  if (path.empty()) throw std::invalid_argument("a band needs a path");
  if ((!along_sd_m.empty() && along_sd_m.size() != path.size()) ||
      (!cross_sd_m.empty() && cross_sd_m.size() != path.size()))
    throw std::invalid_argument("one spread per path point");
  const std::size_t end = std::clamp<std::size_t>(turn_points, 1, path.size()) - 1;
  const double t_end = path[end].t_s;
  const double t0 = path.front().t_s;
  // Directions: each point takes the segment arriving at it; the first the first segment with a
  // length, and a point at rest the direction before it.
  std::vector<Point> dir(path.size(), Point{0.0, 1.0});
  Point last{0.0, 1.0};
  bool found = false;
  for (std::size_t i = 1; i < path.size() && !found; ++i)
    found = unit_of(path[i - 1], path[i], last);
  dir[0] = last;
  for (std::size_t i = 1; i < path.size(); ++i) {
    Point u;
    if (unit_of(path[i - 1], path[i], u)) last = u;
    dir[i] = last;
  }
  const Covariance2& cc = sources.current_covariance_m2ps2;
  std::vector<Covariance2> out(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    // Past the turn its spread is held at the turn's last value.
    const std::size_t k = std::min(i, end);
    const double a_turn = along_sd_m.empty() ? 0.0 : along_sd_m[k];
    const double c_turn = cross_sd_m.empty() ? 0.0 : cross_sd_m[k];
    const double since = std::max(0.0, path[i].t_s - t_end);
    const double a = sources.scatter.along_mps * since, c = sources.scatter.cross_mps * since;
    const double va = a_turn * a_turn + a * a, vc = c_turn * c_turn + c * c;
    const Point u = dir[i];        // along
    const Point n{u.y_m, -u.x_m};  // across (to the right)
    const double t = path[i].t_s - t0;
    const double p2 = sources.position_sd_m * sources.position_sd_m;
    out[i] = {p2 + va * u.x_m * u.x_m + vc * n.x_m * n.x_m + cc[0] * t * t,
              va * u.x_m * u.y_m + vc * n.x_m * n.y_m + cc[1] * t * t,
              p2 + va * u.y_m * u.y_m + vc * n.y_m * n.y_m + cc[2] * t * t};
  }
  return out;
}

double band_radius_factor(double share) {
  if (!(share > 0.0 && share < 1.0)) throw std::invalid_argument("a share must be within (0, 1)");
  return std::sqrt(-2.0 * std::log(1.0 - share));
}

double mahalanobis2(const Covariance2& c, Point d) {
  // A band narrower than a millimetre is a line: the floor keeps the inverse finite.
  constexpr double kFloor = 1e-6;
  const double xx = c[0] + kFloor, xy = c[1], yy = c[2] + kFloor;
  const double det = xx * yy - xy * xy;
  return (yy * d.x_m * d.x_m - 2.0 * xy * d.x_m * d.y_m + xx * d.y_m * d.y_m) / det;
}

BandEllipse band_ellipse(const Covariance2& c, double share) {
  const double k = band_radius_factor(share);
  const double tr = c[0] + c[2], det = c[0] * c[2] - c[1] * c[1];
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4.0 - det));
  const double l1 = std::max(0.0, tr / 2.0 + disc), l2 = std::max(0.0, tr / 2.0 - disc);
  // The major eigenvector's angle from the x axis, then as a heading (clockwise from north).
  const double theta = 0.5 * std::atan2(2.0 * c[1], c[0] - c[2]);
  double heading = 90.0 - theta * 180.0 / std::numbers::pi;
  heading = std::fmod(std::fmod(heading, 180.0) + 180.0, 180.0);
  return {k * std::sqrt(l1), k * std::sqrt(l2), heading};
}

double variance_along(const Covariance2& c, Point n) {
  return c[0] * n.x_m * n.x_m + 2.0 * c[1] * n.x_m * n.y_m + c[2] * n.y_m * n.y_m;
}

}  // namespace avk::kinematics
