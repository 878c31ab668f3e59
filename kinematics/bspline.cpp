#include "kinematics/bspline.hpp"

#include <algorithm>

namespace avk::kinematics::bspline {

std::size_t find_span(const std::vector<double>& knots, std::size_t n_ctrl, double u) {
  if (u >= knots[n_ctrl]) {
    std::size_t k = n_ctrl - 1;
    while (k > kDeg && knots[k] >= knots[k + 1])
      --k;
    return k;
  }
  if (u <= knots[kDeg]) return kDeg;
  const auto first = knots.begin() + static_cast<std::ptrdiff_t>(kDeg);
  const auto last = knots.begin() + static_cast<std::ptrdiff_t>(n_ctrl + 1);
  // The min keeps a NaN parameter (which compares false everywhere) inside the control points.
  return std::min(static_cast<std::size_t>(std::upper_bound(first, last, u) - knots.begin()) - 1,
                  n_ctrl - 1);
}

std::size_t uniform_span(double u, std::size_t intervals) {
  // Truncation is floor for u >= 0, and cheaper than std::floor without SSE4.1.
  const double k = std::clamp(u, 0.0, 1.0) * static_cast<double>(intervals);
  return kDeg + std::min(static_cast<std::size_t>(k), intervals - 1);
}

void basis_derivatives(const std::vector<double>& knots, std::size_t span, double u, int n_derivs,
                       double ders[kOrder][kOrder]) {
  double ndu[kOrder][kOrder];
  double left[kOrder];
  double right[kOrder];
  ndu[0][0] = 1.0;
  for (std::size_t j = 1; j <= kDeg; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    double saved = 0.0;
    for (std::size_t r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (std::size_t j = 0; j <= kDeg; ++j)
    ders[0][j] = ndu[j][kDeg];
  if (n_derivs <= 0) return;
  const int p = static_cast<int>(kDeg);
  double a[2][kOrder] = {};  // zeroed only to reassure -Wmaybe-uninitialized
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n_derivs; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = static_cast<double>(p);
  for (int k = 1; k <= n_derivs; ++k) {
    for (std::size_t j = 0; j <= kDeg; ++j)
      ders[k][j] *= factor;
    factor *= static_cast<double>(p - k);
  }
}

Point combine(const Polyline& ctrl, std::size_t span, const double* b) {
  double x = 0.0;
  double y = 0.0;
  for (std::size_t j = 0; j <= kDeg; ++j) {
    const Point& p = ctrl[span - kDeg + j];
    x += b[j] * p.x_m;
    y += b[j] * p.y_m;
  }
  return {x, y};
}

Point spline_point(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                   double u) {
  double b[kOrder][kOrder];
  basis_derivatives(knots, span, u, 0, b);
  return combine(ctrl, span, b[0]);
}

Point spline_tangent(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                     double u) {
  double b[kOrder][kOrder];
  basis_derivatives(knots, span, u, 1, b);
  return combine(ctrl, span, b[1]);
}

SpanPoly span_poly(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span) {
  SpanPoly out;
  out.u0 = knots[span];
  if (!(knots[span + 1] > knots[span])) return out;  // empty span: never evaluated
  double b[kOrder][kOrder];
  basis_derivatives(knots, span, out.u0, 3, b);
  constexpr double kInverseFactorial[kOrder] = {1.0, 1.0, 0.5, 1.0 / 6.0};
  for (std::size_t d = 0; d < kOrder; ++d) {
    const Point v = combine(ctrl, span, b[d]);
    out.a[d] = {v.x_m * kInverseFactorial[d], v.y_m * kInverseFactorial[d]};
  }
  return out;
}

void to_power_form(const std::vector<double>& knots, const Polyline& ctrl,
                   std::vector<SpanPoly>& out) {
  out.clear();
  for (std::size_t span = kDeg; span < ctrl.size(); ++span)
    out.push_back(span_poly(knots, ctrl, span));
}

void spline_span_bounds(const std::vector<double>& knots, const Polyline& ctrl, std::size_t span,
                        double* speed_bound, double* accel_bound) {
  Point q[kDeg];
  double vmax = 0.0;
  for (std::size_t m = 0; m < kDeg; ++m) {
    const std::size_t i = span - kDeg + m;
    const double dt = knots[i + kDeg + 1] - knots[i + 1];
    const double f = dt > 0.0 ? static_cast<double>(kDeg) / dt : 0.0;
    q[m] = {f * (ctrl[i + 1].x_m - ctrl[i].x_m), f * (ctrl[i + 1].y_m - ctrl[i].y_m)};
    vmax = std::max(vmax, norm(q[m]));
  }
  double amax = 0.0;
  for (std::size_t m = 0; m + 1 < kDeg; ++m) {
    const std::size_t i = span - kDeg + m;
    const double dt = knots[i + kDeg + 1] - knots[i + 2];
    const double f = dt > 0.0 ? static_cast<double>(kDeg - 1) / dt : 0.0;
    amax = std::max(amax, f * norm({q[m + 1].x_m - q[m].x_m, q[m + 1].y_m - q[m].y_m}));
  }
  *speed_bound = vmax;
  *accel_bound = amax;
}

}  // namespace avk::kinematics::bspline
