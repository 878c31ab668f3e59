#include "vehicle/local_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace avk::vehicle {

namespace {

// WGS-84.
constexpr double kA = kWgs84SemiMajorAxis_m;
constexpr double kF = 1.0 / 298.257223563;
constexpr double kE2 = kF * (2.0 - kF);
constexpr double kB = kA * (1.0 - kF);

constexpr double kDeg = std::numbers::pi / 180.0;

// A point on the ellipsoid (height 0), earth-centred earth-fixed.
void to_ecef(double lat_deg, double lon_deg, double out[3]) {
  const double lat = lat_deg * kDeg;
  const double lon = lon_deg * kDeg;
  const double s = std::sin(lat);
  const double n = kA / std::sqrt(1.0 - kE2 * s * s);  // prime vertical radius
  out[0] = n * std::cos(lat) * std::cos(lon);
  out[1] = n * std::cos(lat) * std::sin(lon);
  out[2] = n * (1.0 - kE2) * s;
}

double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Longitude into [-180, 180).
double wrap_lon(double lon_deg) {
  double w = std::fmod(lon_deg + 180.0, 360.0);
  if (w < 0.0) w += 360.0;
  return w - 180.0;
}

}  // namespace

LocalGrid::LocalGrid(double datum_lat_deg, double datum_lon_deg) {
  if (!std::isfinite(datum_lat_deg) || !std::isfinite(datum_lon_deg) ||
      std::abs(datum_lat_deg) > 90.0 || std::abs(datum_lon_deg) > 180.0)
    throw std::invalid_argument("datum " + std::to_string(datum_lat_deg) + ", " +
                                std::to_string(datum_lon_deg) +
                                " is not a latitude in [-90, 90] and longitude in [-180, 180]");
  datum_ = {datum_lat_deg, wrap_lon(datum_lon_deg)};
  to_ecef(datum_.lat_deg, datum_.lon_deg, origin_);
  const double lat = datum_.lat_deg * kDeg;
  const double lon = datum_.lon_deg * kDeg;
  east_[0] = -std::sin(lon);
  east_[1] = std::cos(lon);
  east_[2] = 0.0;
  north_[0] = -std::sin(lat) * std::cos(lon);
  north_[1] = -std::sin(lat) * std::sin(lon);
  north_[2] = std::cos(lat);
  up_[0] = std::cos(lat) * std::cos(lon);
  up_[1] = std::cos(lat) * std::sin(lon);
  up_[2] = std::sin(lat);
}

GridPoint LocalGrid::to_grid(double lat_deg, double lon_deg) const {
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg) || std::abs(lat_deg) > 90.0)
    throw std::invalid_argument("position " + std::to_string(lat_deg) + ", " +
                                std::to_string(lon_deg) + " is not a latitude and longitude");
  double p[3];
  to_ecef(lat_deg, lon_deg, p);
  const double d[3] = {p[0] - origin_[0], p[1] - origin_[1], p[2] - origin_[2]};
  return {dot(d, east_), dot(d, north_)};
}

LatLon LocalGrid::to_geodetic(double x_m, double y_m) const {
  if (!std::isfinite(x_m) || !std::isfinite(y_m))
    throw std::invalid_argument("grid point is not finite");
  // The point is q + u * up for the u that puts it on the ellipsoid: a quadratic in u, of which
  // the root nearest the plane is the one to_grid came from.
  double q[3];
  for (int i = 0; i < 3; ++i)
    q[i] = origin_[i] + x_m * east_[i] + y_m * north_[i];
  const double a2 = kA * kA;
  const double b2 = kB * kB;
  const double qa = (up_[0] * up_[0] + up_[1] * up_[1]) / a2 + up_[2] * up_[2] / b2;
  const double qb = 2.0 * ((q[0] * up_[0] + q[1] * up_[1]) / a2 + q[2] * up_[2] / b2);
  const double qc = (q[0] * q[0] + q[1] * q[1]) / a2 + q[2] * q[2] / b2 - 1.0;
  const double disc = qb * qb - 4.0 * qa * qc;
  // qb > 0 near the datum, so this form of the small root keeps its precision.
  const double denominator = -qb - std::sqrt(std::max(disc, 0.0));
  if (disc < 0.0 || !(qb > 0.0) || denominator == 0.0)
    throw std::out_of_range("grid point " + std::to_string(x_m) + ", " + std::to_string(y_m) +
                            " is off the earth seen from the datum");
  const double u = 2.0 * qc / denominator;
  double p[3];
  for (int i = 0; i < 3; ++i)
    p[i] = q[i] + u * up_[i];
  // On the ellipsoid the normal gives the geodetic latitude in closed form.
  const double horizontal = std::hypot(p[0], p[1]);
  const double lat = std::atan2(p[2], horizontal * (1.0 - kE2));
  const double lon = std::atan2(p[1], p[0]);
  return {lat / kDeg, wrap_lon(lon / kDeg)};
}

}  // namespace avk::vehicle
