// The local grid against values computed without it: ellipsoidal meridian arcs and parallel
// radii (textbook formulas, integrated here), geodesics from GeographicLib's GeodSolve (Karney)
// and local cartesian coordinates from its CartConvert, then round trips and the edges (poles,
// antimeridian, points off the earth).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vehicle/local_grid.hpp"

namespace {

using avk::vehicle::GridPoint;
using avk::vehicle::LatLon;
using avk::vehicle::LocalGrid;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kA = 6378137.0;
constexpr double kF = 1.0 / 298.257223563;
constexpr double kE2 = kF * (2.0 - kF);

// The MIT Sailing Pavilion on the Charles, where the thesis' vehicles ran.
constexpr double kMitLat = 42.3584;
constexpr double kMitLon = -71.0876;

constexpr double kCentimetre = 0.01;
constexpr double kMillimetre = 0.001;

// Radius of curvature of the meridian and of the prime vertical.
double meridian_radius(double lat) {
  const double s = std::sin(lat);
  return kA * (1.0 - kE2) / std::pow(1.0 - kE2 * s * s, 1.5);
}

double prime_vertical_radius(double lat) {
  const double s = std::sin(lat);
  return kA / std::sqrt(1.0 - kE2 * s * s);
}

// Meridian arc length from lat0 to lat1 (radians): the integral of the meridian radius, by
// Simpson's rule.
double meridian_arc(double lat0, double lat1) {
  constexpr int kSteps = 2000;
  const double h = (lat1 - lat0) / kSteps;
  double sum = meridian_radius(lat0) + meridian_radius(lat1);
  for (int i = 1; i < kSteps; ++i)
    sum += (i % 2 ? 4.0 : 2.0) * meridian_radius(lat0 + i * h);
  return sum * h / 3.0;
}

// The latitude d metres north along the meridian from lat0 (radians), by Newton's method.
double latitude_north_by(double lat0, double d) {
  double lat = lat0 + d / meridian_radius(lat0);
  for (int i = 0; i < 6; ++i)
    lat += (d - meridian_arc(lat0, lat)) / meridian_radius(lat);
  return lat;
}

TEST(LocalGrid, DatumIsTheOrigin) {
  const LocalGrid grid(kMitLat, kMitLon);
  const GridPoint p = grid.to_grid(kMitLat, kMitLon);
  EXPECT_NEAR(p.x_m, 0.0, 1e-9);
  EXPECT_NEAR(p.y_m, 0.0, 1e-9);
  const LatLon back = grid.to_geodetic(0.0, 0.0);
  EXPECT_NEAR(back.lat_deg, kMitLat, 1e-12);
  EXPECT_NEAR(back.lon_deg, kMitLon, 1e-12);
  EXPECT_EQ(grid.datum().lat_deg, kMitLat);
}

// Due north, the grid's y is the meridian arc: the plane shortens it by about d^3 / 6R^2, half a
// millimetre at 5 km.
TEST(LocalGrid, NorthMatchesTheMeridianArc) {
  for (double lat0_deg : {kMitLat, 0.0, -33.9, 60.0}) {
    const LocalGrid grid(lat0_deg, kMitLon);
    for (double d = 1000.0; d <= 5000.0; d += 1000.0) {
      for (double sign : {1.0, -1.0}) {
        const double lat1 = latitude_north_by(lat0_deg * kDeg, sign * d);
        const GridPoint p = grid.to_grid(lat1 / kDeg, kMitLon);
        EXPECT_NEAR(p.x_m, 0.0, 1e-6) << lat0_deg << " " << sign * d;
        EXPECT_NEAR(p.y_m, sign * d, kCentimetre) << lat0_deg << " " << sign * d;
        EXPECT_NEAR(p.y_m, sign * d, kMillimetre) << lat0_deg << " " << sign * d;
      }
    }
  }
}

// Along the parallel, x is the parallel's arc N cos(lat) dlon to within a centimetre (the plane
// shortens it by about d^3 / 6 (N cos lat)^2: 2 mm at 5 km and 60 degrees), exactly the chord's
// projection N cos(lat) sin(dlon), and the parallel curves north of the plane's east axis by
// N cos(lat) sin(lat) (1 - cos dlon), about x^2 tan(lat) / 2N (1.8 m at 5 km off the MIT datum).
TEST(LocalGrid, EastMatchesTheParallelArc) {
  for (double lat0_deg : {kMitLat, 0.0, -33.9, 60.0}) {
    const LocalGrid grid(lat0_deg, kMitLon);
    const double lat = lat0_deg * kDeg;
    const double parallel_radius = prime_vertical_radius(lat) * std::cos(lat);
    for (double d = 1000.0; d <= 5000.0; d += 1000.0) {
      for (double sign : {1.0, -1.0}) {
        const double dlon = sign * d / parallel_radius;
        const GridPoint p = grid.to_grid(lat0_deg, kMitLon + dlon / kDeg);
        EXPECT_NEAR(p.x_m, sign * d, kCentimetre) << lat0_deg << " " << sign * d;
        EXPECT_NEAR(p.x_m, parallel_radius * std::sin(dlon), 1e-6) << lat0_deg << " " << sign * d;
        const double rise = parallel_radius * std::sin(lat) * (1.0 - std::cos(dlon));
        EXPECT_NEAR(p.y_m, rise, 1e-6) << lat0_deg << " " << sign * d;
        EXPECT_NEAR(p.y_m, d * d * std::tan(lat) / (2.0 * prime_vertical_radius(lat)), kMillimetre)
            << lat0_deg << " " << sign * d;
      }
    }
  }
}

// Points 1 km and 5 km from the MIT datum at azimuths 0, 45, ..., 315 degrees, solved with
// GeographicLib 2.1.2 (`GeodSolve -p 9`, the direct geodesic problem on WGS-84). On the grid they
// must lie at that distance and azimuth to a centimetre.
TEST(LocalGrid, MatchesGeodesicsFromTheMitDatum) {
  const LatLon at_1km[] = {
      {42.36740249353001, -71.08759999999999}, {42.36476540439482, -71.07901609780411},
      {42.35839935749638, -71.07546175444440}, {42.35203394600825, -71.07901783040421},
      {42.34939749228339, -71.08759999999999}, {42.35203394600825, -71.09618216959578},
      {42.35839935749638, -71.09973824555559}, {42.36476540439482, -71.09618390219588},
  };
  const LatLon at_5km[] = {
      {42.40341232577647, -71.08759999999999}, {42.39022052058556, -71.04466315180005},
      {42.35838393741241, -71.02690878211443}, {42.32656323948567, -71.04470646680693},
      {42.31338731955869, -71.08759999999999}, {42.32656323948567, -71.13049353319306},
      {42.35838393741241, -71.14829121788556}, {42.39022052058556, -71.13053684819994},
  };
  const LocalGrid grid(kMitLat, kMitLon);
  for (int i = 0; i < 8; ++i) {
    const double azimuth = 45.0 * i * kDeg;
    for (const auto& [points, distance] : {std::pair{at_1km, 1000.0}, std::pair{at_5km, 5000.0}}) {
      const GridPoint p = grid.to_grid(points[i]);
      EXPECT_NEAR(p.x_m, distance * std::sin(azimuth), kCentimetre) << i << " " << distance;
      EXPECT_NEAR(p.y_m, distance * std::cos(azimuth), kCentimetre) << i << " " << distance;
      EXPECT_NEAR(std::hypot(p.x_m, p.y_m), distance, kMillimetre) << i << " " << distance;
    }
  }
}

// GeographicLib's local cartesian coordinates (`CartConvert -l 42.3584 -71.0876 0 -p 6`) and
// geodesic distances (`GeodSolve -i`) for a real M200 GPS fix on the Charles
// (4221.71114 N, 07105.44878 W) and three points 3-6 km away.
TEST(LocalGrid, MatchesGeographicLibAroundTheMitDatum) {
  struct Case {
    LatLon position;
    double x_m, y_m, geodesic_m;
  };
  const Case cases[] = {
      {{42.0 + 21.71114 / 60.0, -(71.0 + 5.44878 / 60.0)}, -264.686036, 383.491158, 465.965842},
      {{42.3736, -71.1190}, -2586.241105, 1688.899473, 3088.855003},
      {{42.3300, -71.0500}, 3099.041236, -3153.985939, 4421.728963},
      {{42.3900, -71.0300}, 4742.952459, 3511.751665, 5901.525880},
  };
  const LocalGrid grid(kMitLat, kMitLon);
  for (const Case& c : cases) {
    const GridPoint p = grid.to_grid(c.position);
    EXPECT_NEAR(p.x_m, c.x_m, kMillimetre) << c.position.lat_deg;
    EXPECT_NEAR(p.y_m, c.y_m, kMillimetre) << c.position.lat_deg;
    EXPECT_NEAR(std::hypot(p.x_m, p.y_m), c.geodesic_m, kCentimetre) << c.position.lat_deg;
  }
}

TEST(LocalGrid, RoundTripsGridToGeodeticAndBack) {
  for (const LatLon datum :
       {LatLon{kMitLat, kMitLon}, LatLon{0.0, 0.0}, LatLon{-45.5, 170.25}, LatLon{78.2, 15.6}}) {
    const LocalGrid grid(datum.lat_deg, datum.lon_deg);
    double worst = 0.0;
    for (double x = -5000.0; x <= 5000.0; x += 250.0) {
      for (double y = -5000.0; y <= 5000.0; y += 250.0) {
        const GridPoint back = grid.to_grid(grid.to_geodetic(x, y));
        worst = std::max({worst, std::abs(back.x_m - x), std::abs(back.y_m - y)});
      }
    }
    EXPECT_LT(worst, kMillimetre) << datum.lat_deg << " " << datum.lon_deg;
    EXPECT_LT(worst, 1e-6) << datum.lat_deg << " " << datum.lon_deg;  // the inverse is exact
    // Far beyond a mission area the plane still inverts exactly.
    for (const GridPoint far : {GridPoint{50e3, -20e3}, GridPoint{-300e3, 400e3}}) {
      const GridPoint back = grid.to_grid(grid.to_geodetic(far));
      EXPECT_NEAR(back.x_m, far.x_m, kMillimetre);
      EXPECT_NEAR(back.y_m, far.y_m, kMillimetre);
    }
  }
}

TEST(LocalGrid, RoundTripsGeodeticToGridAndBack) {
  const LocalGrid grid(kMitLat, kMitLon);
  for (double dlat = -0.05; dlat <= 0.05; dlat += 0.01) {
    for (double dlon = -0.06; dlon <= 0.06; dlon += 0.01) {
      const LatLon back = grid.to_geodetic(grid.to_grid(kMitLat + dlat, kMitLon + dlon));
      EXPECT_NEAR(back.lat_deg, kMitLat + dlat, 1e-11);
      EXPECT_NEAR(back.lon_deg, kMitLon + dlon, 1e-11);
    }
  }
}

TEST(LocalGrid, CrossesTheAntimeridian) {
  const LocalGrid grid(10.0, 179.99);
  const GridPoint p = grid.to_grid(10.0, -179.99);  // 0.02 degrees east, across the line
  const double parallel_radius = prime_vertical_radius(10.0 * kDeg) * std::cos(10.0 * kDeg);
  EXPECT_NEAR(p.x_m, parallel_radius * 0.02 * kDeg, kCentimetre);
  EXPECT_GT(p.x_m, 2000.0);
  const LatLon back = grid.to_geodetic(p);
  EXPECT_NEAR(back.lon_deg, -179.99, 1e-11);
  // A datum written as +180 is the same as -180.
  const LocalGrid at_180(0.0, 180.0);
  EXPECT_NEAR(at_180.to_grid(0.0, -180.0).x_m, 0.0, 1e-6);
  EXPECT_EQ(at_180.datum().lon_deg, -180.0);
}

TEST(LocalGrid, WorksAtThePoles) {
  const LocalGrid grid(90.0, 0.0);
  // From the north pole every direction is south; longitude 90 E lies along the grid's x axis.
  const double lat = latitude_north_by(90.0 * kDeg, -3000.0) / kDeg;
  const GridPoint p = grid.to_grid(lat, 90.0);
  EXPECT_NEAR(p.x_m, 3000.0, kMillimetre);
  EXPECT_NEAR(p.y_m, 0.0, 1e-6);
  const LatLon back = grid.to_geodetic(p);
  EXPECT_NEAR(back.lat_deg, lat, 1e-11);
  EXPECT_NEAR(back.lon_deg, 90.0, 1e-9);
  EXPECT_NEAR(grid.to_geodetic(0.0, 0.0).lat_deg, 90.0, 1e-12);
}

TEST(LocalGrid, RejectsBadInput) {
  EXPECT_THROW(LocalGrid(91.0, 0.0), std::invalid_argument);
  EXPECT_THROW(LocalGrid(0.0, 180.5), std::invalid_argument);
  EXPECT_THROW(LocalGrid(std::nan(""), 0.0), std::invalid_argument);
  const LocalGrid grid(kMitLat, kMitLon);
  EXPECT_THROW(grid.to_grid(90.5, 0.0), std::invalid_argument);
  EXPECT_THROW(grid.to_grid(0.0, HUGE_VAL), std::invalid_argument);
  EXPECT_THROW(grid.to_geodetic(std::nan(""), 0.0), std::invalid_argument);
  EXPECT_THROW(grid.to_geodetic(1e8, 0.0), std::out_of_range);   // beyond the earth
  EXPECT_THROW(grid.to_geodetic(0.0, -2e7), std::out_of_range);  // the far side
  EXPECT_NO_THROW(grid.to_grid(0.0, 541.0));                     // longitudes wrap
}

}  // namespace
