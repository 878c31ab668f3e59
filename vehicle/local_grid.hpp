#pragma once
// The local grid of navigation: x east, y north, metres from a datum (the lat/lon origin the
// mission is configured with). A local tangent plane on the WGS-84 ellipsoid: a point on the
// ellipsoid goes to earth-centred coordinates and then to east/north about the datum, the
// up component dropped; the inverse puts (x, y) back on the ellipsoid along the datum's up
// direction, in closed form. Over a few km, distances on the grid match ellipsoidal geodesic
// distances to a millimetre or so (the plane shortens a distance s by about s^3 / 6R^2:
// 0.5 mm at 5 km, 6 cm at 25 km), which is what a turn table built from grid tracks needs.
//
// GeographicLib's LocalCartesian computes the same plane (Debian ships it as
// libgeographiclib-dev); a dependency for twenty lines of closed-form geometry was not worth it.

namespace avk::vehicle {

// WGS-84's semi-major axis, the earth's equatorial radius.
inline constexpr double kWgs84SemiMajorAxis_m = 6378137.0;

struct LatLon {
  double lat_deg = 0.0;  // + north
  double lon_deg = 0.0;  // + east, in [-180, 180)
};

struct GridPoint {
  double x_m = 0.0;  // east
  double y_m = 0.0;  // north
};

class LocalGrid {
 public:
  // Throws std::invalid_argument for a datum that is not finite, |lat| > 90 or |lon| > 180.
  LocalGrid(double datum_lat_deg, double datum_lon_deg);

  const LatLon& datum() const { return datum_; }

  // Throws std::invalid_argument for a position that is not finite or |lat| > 90. Any longitude
  // is taken (it wraps), so positions across the antimeridian need no care from the caller.
  GridPoint to_grid(double lat_deg, double lon_deg) const;
  GridPoint to_grid(const LatLon& p) const { return to_grid(p.lat_deg, p.lon_deg); }

  // Throws std::out_of_range when (x, y) is off the earth as seen from the datum (more than
  // about 6000 km away), and std::invalid_argument when not finite.
  LatLon to_geodetic(double x_m, double y_m) const;
  LatLon to_geodetic(const GridPoint& p) const { return to_geodetic(p.x_m, p.y_m); }

 private:
  LatLon datum_;
  double origin_[3];  // the datum, earth-centred earth-fixed, metres
  double east_[3];    // unit vectors of the plane, earth-centred axes
  double north_[3];
  double up_[3];
};

}  // namespace avk::vehicle
