#pragma once
// Clamped cubic B-spline primitives (The NURBS Book, A2.1-A2.3) for the arc length spline of
// kinematics/curve_fit.hpp: locating the span of a parameter, the basis functions and their
// derivatives, evaluation, the power form of one span and bounds of its derivatives.

#include <cmath>
#include <cstddef>
#include <vector>

#include "kinematics/curve_fit.hpp"
#include "kinematics/geometry.hpp"

namespace avk::kinematics::bspline {

inline constexpr std::size_t kDeg = kSplineDegree;
inline constexpr std::size_t kOrder = kDeg + 1;

// Index k with knots[k] <= u < knots[k+1] and a non-empty span; the last span also takes u at
// the right end so the curve is closed on its domain.
std::size_t find_span(const std::vector<double>& knots, std::size_t n_ctrl, double u);

// find_span for the uniform knots used while fitting (interior knots k / intervals): no search.
std::size_t uniform_span(double u, std::size_t intervals);

// ders[d][j]: d-th derivative (d <= n_derivs <= 3) of the basis function of control point
// span - 3 + j at u. O(degree^2); no allocation.
void basis_derivatives(const std::vector<double>& knots, std::size_t span, double u, int n_derivs,
                       double ders[kOrder][kOrder]);

struct SplinePoint {
  Point c;   // C(u)
  Point d1;  // C'(u)
  Point d2;  // C''(u)
};

// Sum of the control points of a span weighted by basis row b.
Point combine(const Polyline& ctrl, std::size_t span, const double* b);

Point spline_point(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                   double u);
Point spline_tangent(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                     double u);

// One span in power form about its start, C(u0 + t) = a0 + a1 t + a2 t^2 + a3 t^3: evaluating C,
// C' and C'' then costs a dozen flops instead of the Cox-de Boor recursion, which matters in the
// projection and sampling loops that evaluate every span many times.
struct SpanPoly {
  double u0 = 0.0;
  Point a[kOrder];

  Point point(double u) const {
    const double t = u - u0;
    return {a[0].x_m + t * (a[1].x_m + t * (a[2].x_m + t * a[3].x_m)),
            a[0].y_m + t * (a[1].y_m + t * (a[2].y_m + t * a[3].y_m))};
  }
  SplinePoint derivatives(double u) const {
    const double t = u - u0;
    return {point(u),
            {a[1].x_m + t * (2.0 * a[2].x_m + 3.0 * t * a[3].x_m),
             a[1].y_m + t * (2.0 * a[2].y_m + 3.0 * t * a[3].y_m)},
            {2.0 * a[2].x_m + 6.0 * t * a[3].x_m, 2.0 * a[2].y_m + 6.0 * t * a[3].y_m}};
  }
};
SpanPoly span_poly(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span);

// Entry k is span kDeg + k.
void to_power_form(const std::vector<double>& knots, const Polyline& ctrl,
                   std::vector<SpanPoly>& out);

// Plain sqrt: hypot's overflow guard costs several times more and metre-scale vectors never
// need it.
inline double norm(Point v) {
  return std::sqrt(v.x_m * v.x_m + v.y_m * v.y_m);
}

// Bounds of |C'| and |C''| over one span from the convex hull property of the derivative
// curves, whose control points are scaled differences of the control points.
void spline_span_bounds(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                        double* speed_bound, double* accel_bound);

}  // namespace avk::kinematics::bspline
