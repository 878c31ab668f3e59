#include "kinematics/curve_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

namespace {

constexpr std::size_t kDeg = kSplineDegree;
constexpr std::size_t kOrder = kDeg + 1;

// ---- cubic B-spline primitives (The NURBS Book, A2.1-A2.3) ----------------------------------

// Index k with knots[k] <= u < knots[k+1] and a non-empty span; the last span also takes u at
// the right end so the curve is closed on its domain.
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

// find_span for the uniform knots used while fitting (interior knots k / intervals): no search.
std::size_t uniform_span(double u, std::size_t intervals) {
  // Truncation is floor for u >= 0, and cheaper than std::floor without SSE4.1.
  const double k = std::clamp(u, 0.0, 1.0) * static_cast<double>(intervals);
  return kDeg + std::min(static_cast<std::size_t>(k), intervals - 1);
}

// ders[d][j]: d-th derivative (d <= n_derivs <= 3) of the basis function of control point
// span - 3 + j at u. O(degree^2); no allocation.
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

struct SplinePoint {
  Point c;   // C(u)
  Point d1;  // C'(u)
  Point d2;  // C''(u)
};

// Sum of the control points of a span weighted by basis row b.
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

// Entry k is span kDeg + k.
void to_power_form(const std::vector<double>& knots, const Polyline& ctrl,
                   std::vector<SpanPoly>& out) {
  out.clear();
  for (std::size_t span = kDeg; span < ctrl.size(); ++span)
    out.push_back(span_poly(knots, ctrl, span));
}

// Plain sqrt: hypot's overflow guard costs several times more and metre-scale vectors never
// need it.
double norm(Point v) {
  return std::sqrt(v.x_m * v.x_m + v.y_m * v.y_m);
}

// Bounds of |C'| and |C''| over one span from the convex hull property of the derivative
// curves, whose control points are scaled differences of the control points.
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

// Arc length as a function of the spline parameter. Speed and its derivative are taken at nodes
// spread evenly over each span, integrated with the end-corrected trapezoid rule and
// interpolated between nodes by cubic Hermite (both O(h^4)), so a lookup needs no spline
// evaluation: converting every sample to its arc length position is the hot loop of a fit.
class ArcLengthTable {
 public:
  void build(const std::vector<double>& knots, const std::vector<SpanPoly>& polys) {
    constexpr std::size_t kNodesPerSpan = 8;
    const std::size_t n_ctrl = polys.size() + kDeg;
    u_.clear();
    s_.clear();
    v_.clear();
    dv_.clear();
    const auto add_node = [&](std::size_t span, double u) {
      const SplinePoint sp = polys[span - kDeg].derivatives(u);
      const double v = norm(sp.d1);
      const double dv = v > 0.0 ? (sp.d1.x_m * sp.d2.x_m + sp.d1.y_m * sp.d2.y_m) / v : 0.0;
      double s = 0.0;
      if (!u_.empty()) {
        const double h = u - u_.back();
        s = s_.back() + 0.5 * h * (v_.back() + v) + h * h / 12.0 * (dv_.back() - dv);
      }
      u_.push_back(u);
      s_.push_back(s);
      v_.push_back(v);
      dv_.push_back(dv);
    };
    add_node(kDeg, knots[kDeg]);
    for (std::size_t span = kDeg; span < n_ctrl; ++span) {
      const double u0 = knots[span];
      const double u1 = knots[span + 1];
      if (!(u1 > u0)) continue;
      for (std::size_t j = 1; j <= kNodesPerSpan; ++j) {
        const double u =
            j == kNodesPerSpan ? u1 : u0 + (u1 - u0) * static_cast<double>(j) / kNodesPerSpan;
        add_node(span, u);
      }
    }
  }
  double total() const { return s_.back(); }
  double at(double u) const {
    if (u <= u_.front()) return 0.0;
    if (u >= u_.back()) return s_.back();
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(u_.begin(), u_.end(), u) - u_.begin()) - 1;
    const double h = u_[i + 1] - u_[i];
    const double t = (u - u_[i]) / h;
    const double t2 = t * t;
    const double t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * s_[i] + (t3 - 2 * t2 + t) * h * v_[i] +
           (-2 * t3 + 3 * t2) * s_[i + 1] + (t3 - t2) * h * v_[i + 1];
  }

 private:
  std::vector<double> u_, s_, v_, dv_;
};

// ---- poly4 primitives -----------------------------------------------------------------------

double poly_value(const std::vector<double>& c, double t) {
  return (((c[4] * t + c[3]) * t + c[2]) * t + c[1]) * t + c[0];
}
double poly_d1(const std::vector<double>& c, double t) {
  return ((4.0 * c[4] * t + 3.0 * c[3]) * t + 2.0 * c[2]) * t + c[1];
}
double poly_d2(const std::vector<double>& c, double t) {
  return (12.0 * c[4] * t + 6.0 * c[3]) * t + 2.0 * c[2];
}

// Max of |g'| and |g''| over [t0, t1] in the scaled variable: both are low-degree polynomials,
// so their extremes are at the ends or at the roots of the next derivative.
void poly_piece_bounds(const std::vector<double>& c, double t0, double t1, double* d1_max,
                       double* d2_max) {
  double m1 = std::max(std::abs(poly_d1(c, t0)), std::abs(poly_d1(c, t1)));
  double m2 = std::max(std::abs(poly_d2(c, t0)), std::abs(poly_d2(c, t1)));
  const auto consider_d1 = [&](double t) {
    if (t > t0 && t < t1) m1 = std::max(m1, std::abs(poly_d1(c, t)));
  };
  // g'' = 12 c4 t^2 + 6 c3 t + 2 c2
  const double qa = 12.0 * c[4];
  const double qb = 6.0 * c[3];
  const double qc = 2.0 * c[2];
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      consider_d1((-qb + sq) / (2.0 * qa));
      consider_d1((-qb - sq) / (2.0 * qa));
    }
    const double tv = -qb / (2.0 * qa);  // vertex of g''
    if (tv > t0 && tv < t1) m2 = std::max(m2, std::abs(poly_d2(c, tv)));
  } else if (qb != 0.0) {
    consider_d1(-qc / qb);
  }
  *d1_max = m1;
  *d2_max = m2;
}

// Number of equal sub-steps for a piece of parameter width w where the curve moves at most
// speed_bound per unit parameter and bends at most accel_bound: the chord of a sub-step h is at
// most speed_bound h long and strays at most accel_bound h^2 / 8 from the curve.
std::size_t substeps(double w, double speed_bound, double accel_bound, double max_step_m,
                     double max_chord_error_m) {
  double n = 1.0;
  if (std::isfinite(max_step_m)) n = std::max(n, std::ceil(w * speed_bound / max_step_m));
  if (std::isfinite(max_chord_error_m) && accel_bound > 0.0)
    n = std::max(n, std::ceil(w * std::sqrt(accel_bound / (8.0 * max_chord_error_m))));
  return static_cast<std::size_t>(n);
}

[[noreturn]] void bad_field(const char* field, const std::string& why) {
  throw std::invalid_argument(std::string("CurveFit.") + field + ": " + why);
}

void require_finite(const Polyline& points, const char* who) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x_m) || !std::isfinite(points[i].y_m))
      throw std::invalid_argument(std::string(who) + ": non-finite coordinate at point " +
                                  std::to_string(i));
  }
}

// Length of the path ignoring sample-to-sample jitter: only steps of at least min_step_m are
// counted, because GNSS noise inflates the chord length of dense samples several times over.
double robust_length_m(const Polyline& points, double min_step_m) {
  double length = 0.0;
  Point last = points.front();
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double d = norm({points[i].x_m - last.x_m, points[i].y_m - last.y_m});
    if (d >= min_step_m || i + 1 == points.size()) {
      length += d;
      last = points[i];
    }
  }
  return length;
}

// Least squares by block Householder QR along the band (the sequential scheme of FITPACK, with
// reflections instead of rotations): rows touching columns c..c+3 are stacked under the
// unfinished part of R and reduced with 4 reflections, after which row c of R is final and the
// other 3 carry over to the next block. Cost is linear in the number of rows, with 4 square
// roots per knot interval instead of a dense pass over every column. Orthogonal throughout, so
// the condition number is that of the system, never its square as with the normal equations.
class BandedLeastSquares {
 public:
  static constexpr Eigen::Index kCols = kOrder + 2;  // 4 band columns, then the x and y sides

  void start(std::size_t columns, std::size_t max_block_rows) {
    n_ = columns;
    r_.assign(n_ * kOrder, 0.0);
    qtb_.assign(n_ * 2, 0.0);
    const auto rows = static_cast<Eigen::Index>(max_block_rows + kOrder);
    if (work_.rows() < rows) work_.resize(rows, kCols);
    carry_.setZero();
  }

  // Row i of the next block (call reduce_block after filling m rows).
  auto block_row(std::size_t i) { return work_.row(static_cast<Eigen::Index>(kOrder + i)); }

  // Reduces the m rows filled through block_row, all within columns c .. c+3; c must grow by one
  // from 0 to columns - 4.
  void reduce_block(std::size_t c, std::size_t m) {
    const auto rows = static_cast<Eigen::Index>(kOrder + m);
    auto w = work_.topRows(rows);
    w.topRows(kOrder) = carry_;
    double workspace[kCols];
    for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(kOrder); ++k) {
      double tau = 0.0;
      double beta = 0.0;
      w.col(k).tail(rows - k).makeHouseholderInPlace(tau, beta);
      w(k, k) = beta;
      w.bottomRightCorner(rows - k, kCols - k - 1)
          .applyHouseholderOnTheLeft(w.col(k).tail(rows - k - 1), tau, workspace);
    }
    const bool last = c + kOrder == n_;
    for (std::size_t i = 0; i < (last ? kOrder : 1); ++i) {
      const auto wi = static_cast<Eigen::Index>(i);
      for (std::size_t k = i; k < kOrder; ++k)
        r_[(c + i) * kOrder + (k - i)] = w(wi, static_cast<Eigen::Index>(k));
      qtb_[(c + i) * 2] = w(wi, kOrder);
      qtb_[(c + i) * 2 + 1] = w(wi, kOrder + 1);
    }
    // Rows 1..3 move up a row and left a column: their next column enters with zeros.
    carry_.setZero();
    for (Eigen::Index i = 0; i + 1 < static_cast<Eigen::Index>(kOrder); ++i) {
      for (Eigen::Index k = 1; k < static_cast<Eigen::Index>(kOrder); ++k)
        carry_(i, k - 1) = w(i + 1, k);
      carry_(i, kOrder) = w(i + 1, kOrder);
      carry_(i, kOrder + 1) = w(i + 1, kOrder + 1);
    }
  }

  // Back substitution; false if R is singular (too few distinct parameters).
  bool solve(Polyline& out) const {
    out.assign(n_, Point{});
    double largest = 0.0;
    for (std::size_t i = 0; i < n_; ++i)
      largest = std::max(largest, std::abs(r_[i * kOrder]));
    for (std::size_t i = n_; i-- > 0;) {
      const double* ri = &r_[i * kOrder];
      if (!(std::abs(ri[0]) > 1e-13 * largest)) return false;
      double x = qtb_[i * 2];
      double y = qtb_[i * 2 + 1];
      for (std::size_t k = 1; k < kOrder && i + k < n_; ++k) {
        x -= ri[k] * out[i + k].x_m;
        y -= ri[k] * out[i + k].y_m;
      }
      out[i] = {x / ri[0], y / ri[0]};
    }
    return true;
  }

 private:
  std::size_t n_ = 0;
  std::vector<double> r_;    // r_[i * 4 + k] = R(i, i + k)
  std::vector<double> qtb_;  // Q^T b for the x and y sides
  Eigen::Matrix<double, Eigen::Dynamic, kCols> work_;
  Eigen::Matrix<double, kOrder, kCols> carry_;
};

// Control points for samples at parameters u (in [0, 1]) with the jerk penalty. `order` and
// `span_start` are scratch space for bucketing the samples by knot span.
void solve_control_points(const Polyline& points, const std::vector<double>& u,
                          const std::vector<double>& knots, std::size_t intervals,
                          double penalty_weight, BandedLeastSquares& ls,
                          std::vector<std::size_t>& order, std::vector<std::size_t>& span_start,
                          Polyline& ctrl) {
  const std::size_t n_ctrl = intervals + kDeg;
  // Counting sort of the samples by span: projection can reorder noisy samples.
  span_start.assign(intervals + 1, 0);
  order.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    ++span_start[uniform_span(u[i], intervals) - kDeg + 1];
  std::size_t max_rows = 0;
  for (std::size_t k = 0; k < intervals; ++k) {
    max_rows = std::max(max_rows, span_start[k + 1]);
    span_start[k + 1] += span_start[k];
  }
  {
    std::vector<std::size_t>& next = span_start;  // advanced while filling, restored below
    for (std::size_t i = 0; i < points.size(); ++i)
      order[next[uniform_span(u[i], intervals) - kDeg]++] = i;
    for (std::size_t k = intervals; k-- > 1;)
      next[k] = next[k - 1];
    next[0] = 0;
  }
  ls.start(n_ctrl, max_rows + 1);
  double b[kOrder][kOrder];
  for (std::size_t k = 0; k < intervals; ++k) {
    const std::size_t span = kDeg + k;
    const std::size_t first = span_start[k];
    const std::size_t count = span_start[k + 1] - first;
    // The 4 basis functions of a span as cubics in u - u0 (Taylor coefficients at the span start):
    // a row then costs 4 Horner evaluations instead of the recursion with its divisions.
    const double u0 = knots[span];
    basis_derivatives(knots, span, u0, 3, b);
    for (std::size_t c = 0; c < kOrder; ++c) {
      b[2][c] *= 0.5;
      b[3][c] *= 1.0 / 6.0;
    }
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t i = order[first + j];
      const double t = u[i] - u0;
      auto row = ls.block_row(j);
      for (std::size_t c = 0; c < kOrder; ++c)
        row(static_cast<Eigen::Index>(c)) = ((b[3][c] * t + b[2][c]) * t + b[1][c]) * t + b[0][c];
      row(kOrder) = points[i].x_m;
      row(kOrder + 1) = points[i].y_m;
    }
    // C''' is constant inside a span, so one row per span integrates |C'''|^2 exactly.
    const double width = knots[span + 1] - knots[span];
    const double w = std::sqrt(penalty_weight * width);
    auto row = ls.block_row(count);
    for (std::size_t c = 0; c < kOrder; ++c)
      row(static_cast<Eigen::Index>(c)) = w * 6.0 * b[3][c];
    row(kOrder) = 0.0;
    row(kOrder + 1) = 0.0;
    ls.reduce_block(k, count + 1);
  }
  if (!ls.solve(ctrl))
    throw std::invalid_argument("fit_arc_length_spline: singular system (degenerate samples)");
}

}  // namespace

const char* to_string(FitKind kind) {
  switch (kind) {
    case FitKind::poly4_xy:
      return "poly4_xy";
    case FitKind::arc_length_spline:
      return "arc_length_spline";
  }
  return "?";
}

std::optional<FitKind> fit_kind_from_string(std::string_view name) {
  if (name == "poly4_xy") return FitKind::poly4_xy;
  if (name == "arc_length_spline") return FitKind::arc_length_spline;
  return std::nullopt;
}

void CurveFit::check() const {
  if (kind != FitKind::poly4_xy && kind != FitKind::arc_length_spline)
    bad_field("kind", "unknown fit kind " + std::to_string(static_cast<int>(kind)));
  if (!std::isfinite(domain_min)) bad_field("domain_min", "not finite");
  if (!std::isfinite(domain_max)) bad_field("domain_max", "not finite");
  if (!(domain_max > domain_min)) bad_field("domain_max", "must be greater than domain_min");
  for (double c : coefficients)
    if (!std::isfinite(c)) bad_field("coefficients", "not finite");
  for (double k : knots)
    if (!std::isfinite(k)) bad_field("knots", "not finite");
  for (const Point& p : control_points)
    if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m)) bad_field("control_points", "not finite");

  if (kind == FitKind::poly4_xy) {
    if (coefficients.size() != kPoly4CoefficientCount)
      bad_field("coefficients", "poly4_xy needs 5, got " + std::to_string(coefficients.size()));
    if (!std::isfinite(center)) bad_field("center", "not finite");
    if (!std::isfinite(scale) || !(scale > 0.0)) bad_field("scale", "must be finite and > 0");
    if (!knots.empty()) bad_field("knots", "must be empty for poly4_xy");
    if (!control_points.empty()) bad_field("control_points", "must be empty for poly4_xy");
    return;
  }
  if (!coefficients.empty()) bad_field("coefficients", "must be empty for arc_length_spline");
  if (control_points.size() < kOrder)
    bad_field("control_points",
              "a cubic spline needs at least 4, got " + std::to_string(control_points.size()));
  if (knots.size() != control_points.size() + kOrder)
    bad_field("knots",
              "expected control_points + 4 = " + std::to_string(control_points.size() + kOrder) +
                  ", got " + std::to_string(knots.size()));
  for (std::size_t i = 1; i < knots.size(); ++i)
    if (knots[i] < knots[i - 1])
      bad_field("knots", "not non-decreasing at index " + std::to_string(i));
  for (std::size_t i = 0; i < kOrder; ++i) {
    if (knots[i] != domain_min) bad_field("knots", "first 4 knots must equal domain_min");
    if (knots[knots.size() - 1 - i] != domain_max)
      bad_field("knots", "last 4 knots must equal domain_max");
  }
}

Point CurveFit::evaluate(double parameter) const {
  const double p = std::clamp(parameter, domain_min, domain_max);
  if (kind == FitKind::poly4_xy) {
    if (coefficients.size() != kPoly4CoefficientCount) check();
    return {p, poly_value(coefficients, (p - center) / scale)};
  }
  if (knots.size() != control_points.size() + kOrder || control_points.size() < kOrder) check();
  const std::size_t span = find_span(knots, control_points.size(), p);
  return spline_point(knots, control_points, span, p);
}

double CurveFit::heading_deg_at(double parameter) const {
  const double p = std::clamp(parameter, domain_min, domain_max);
  Point d;
  if (kind == FitKind::poly4_xy) {
    if (coefficients.size() != kPoly4CoefficientCount) check();
    d = {1.0, poly_d1(coefficients, (p - center) / scale) / scale};
  } else {
    if (knots.size() != control_points.size() + kOrder || control_points.size() < kOrder) check();
    const std::size_t span = find_span(knots, control_points.size(), p);
    d = spline_tangent(knots, control_points, span, p);
  }
  const double h = heading_of_deg(d.x_m, d.y_m);
  return h >= 270.0 ? h - 360.0 : h;
}

Polyline CurveFit::sample(double max_step_m) const {
  return sample(max_step_m, std::numeric_limits<double>::infinity());
}

Polyline CurveFit::sample(double max_step_m, double max_chord_error_m) const {
  if (!(max_step_m > 0.0)) throw std::invalid_argument("CurveFit::sample: max_step_m must be > 0");
  if (!(max_chord_error_m > 0.0))
    throw std::invalid_argument("CurveFit::sample: max_chord_error_m must be > 0");
  Polyline out;
  if (kind == FitKind::poly4_xy) {
    if (coefficients.size() != kPoly4CoefficientCount) check();
    // Pieces let the step follow the curvature: a fit of a normalised turn is steep near the
    // lead-in and flat elsewhere.
    constexpr int kPieces = 16;
    const double width = (domain_max - domain_min) / kPieces;
    const double t_width = width / scale;
    std::size_t counts[kPieces];
    std::size_t total = 1;
    for (int k = 0; k < kPieces; ++k) {
      const double t0 = (domain_min + k * width - center) / scale;
      double g1 = 0.0;
      double g2 = 0.0;
      poly_piece_bounds(coefficients, t0, t0 + t_width, &g1, &g2);
      const double f1 = g1 / scale;
      const double f2 = g2 / (scale * scale);
      counts[k] = substeps(width, std::sqrt(1.0 + f1 * f1), f2, max_step_m, max_chord_error_m);
      total += counts[k];
    }
    out.reserve(total);
    out.push_back(evaluate(domain_min));
    for (int k = 0; k < kPieces; ++k) {
      const double x0 = domain_min + k * width;
      const double x1 = k + 1 == kPieces ? domain_max : x0 + width;
      const double h = (x1 - x0) / static_cast<double>(counts[k]);
      for (std::size_t j = 1; j <= counts[k]; ++j) {
        const double x = j == counts[k] ? x1 : x0 + static_cast<double>(j) * h;
        out.push_back({x, poly_value(coefficients, (x - center) / scale)});
      }
    }
    return out;
  }
  if (knots.size() != control_points.size() + kOrder || control_points.size() < kOrder) check();
  const std::size_t n_ctrl = control_points.size();
  std::size_t total = 1;
  for (int pass = 0; pass < 2; ++pass) {
    // Pass 0 counts so the output is allocated once; pass 1 fills it.
    if (pass == 1) {
      out.reserve(total);
      out.push_back(spline_point(knots, control_points, kDeg, knots[kDeg]));
    }
    for (std::size_t span = kDeg; span < n_ctrl; ++span) {
      const double u0 = knots[span];
      const double u1 = knots[span + 1];
      if (!(u1 > u0)) continue;
      double v = 0.0;
      double acc = 0.0;
      spline_span_bounds(knots, control_points, span, &v, &acc);
      const std::size_t n = substeps(u1 - u0, v, acc, max_step_m, max_chord_error_m);
      if (pass == 0) {
        total += n;
        continue;
      }
      const SpanPoly poly = span_poly(knots, control_points, span);
      const double h = (u1 - u0) / static_cast<double>(n);
      for (std::size_t j = 1; j < n; ++j)
        out.push_back(poly.point(u0 + static_cast<double>(j) * h));
      // The span end from the basis, not the power form, so it equals evaluate() there exactly.
      out.push_back(spline_point(knots, control_points, span, u1));
    }
  }
  return out;
}

double estimate_position_noise_m(const Polyline& points) {
  if (points.size() < 4) return 0.0;
  std::vector<double> d3;
  d3.reserve(points.size() - 3);
  for (std::size_t i = 3; i < points.size(); ++i) {
    const auto third = [&](double Point::*c) {
      return points[i].*c - 3.0 * points[i - 1].*c + 3.0 * points[i - 2].*c - points[i - 3].*c;
    };
    d3.push_back(norm({third(&Point::x_m), third(&Point::y_m)}));
  }
  const auto mid = d3.begin() + static_cast<std::ptrdiff_t>(d3.size() / 2);
  std::nth_element(d3.begin(), mid, d3.end());
  // Each coordinate of the third difference has variance (1 + 9 + 9 + 1) sigma^2, so its norm is
  // Rayleigh with scale sqrt(20) sigma and median sqrt(20) * sqrt(2 ln 2) sigma.
  return *mid / (std::sqrt(20.0) * std::sqrt(2.0 * std::log(2.0)));
}

CurveFit fit_poly4(const Polyline& points) {
  require_finite(points, "fit_poly4");
  std::vector<double> xs;
  xs.reserve(points.size());
  for (const Point& p : points)
    xs.push_back(p.x_m);
  std::sort(xs.begin(), xs.end());
  const std::size_t distinct =
      static_cast<std::size_t>(std::unique(xs.begin(), xs.end()) - xs.begin());
  if (distinct < kPoly4CoefficientCount)
    throw std::invalid_argument("fit_poly4: need at least 5 distinct x, got " +
                                std::to_string(distinct));
  CurveFit fit;
  fit.kind = FitKind::poly4_xy;
  fit.domain_min = xs.front();
  fit.domain_max = xs[distinct - 1];
  fit.center = 0.5 * (fit.domain_min + fit.domain_max);
  fit.scale = 0.5 * (fit.domain_max - fit.domain_min);
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd v(n, static_cast<Eigen::Index>(kPoly4CoefficientCount));
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Point& p = points[static_cast<std::size_t>(i)];
    const double t = (p.x_m - fit.center) / fit.scale;
    double power = 1.0;
    for (Eigen::Index k = 0; k < v.cols(); ++k) {
      v(i, k) = power;
      power *= t;
    }
    y(i) = p.y_m;
  }
  const Eigen::VectorXd c = v.colPivHouseholderQr().solve(y);
  fit.coefficients.assign(c.data(), c.data() + c.size());
  return fit;
}

CurveFit fit_arc_length_spline(const Polyline& points, const ArcSplineOptions& options) {
  require_finite(points, "fit_arc_length_spline");
  if (!(options.knot_spacing_m > 0.0) || options.min_intervals < 1 ||
      options.max_intervals < options.min_intervals || !(options.smoothing_m6 > 0.0) ||
      !(options.noise_smoothing_gain >= 0.0) || options.parameter_iterations < 0)
    throw std::invalid_argument("fit_arc_length_spline: inconsistent ArcSplineOptions");
  const std::size_t n_points = points.size();
  // Chord length as the first parameter.
  std::vector<double> u(n_points, 0.0);
  for (std::size_t i = 1; i < n_points; ++i)
    u[i] = u[i - 1] + norm({points[i].x_m - points[i - 1].x_m, points[i].y_m - points[i - 1].y_m});
  // The jerk penalty leaves quadratics free, so three distinct positions are needed.
  std::size_t distinct = u.empty() ? 0 : 1;
  for (std::size_t i = 1; i < u.size(); ++i)
    if (u[i] > u[i - 1]) ++distinct;
  if (distinct < 3)
    throw std::invalid_argument("fit_arc_length_spline: need at least 3 distinct points, got " +
                                std::to_string(distinct));
  const double chord_total = u.back();
  for (double& v : u)
    v /= chord_total;

  double length = robust_length_m(points, options.knot_spacing_m);
  if (!(length > 0.0)) length = chord_total;  // a loop back to the start within one knot step
  const auto wanted = static_cast<std::size_t>(std::lround(length / options.knot_spacing_m));
  const std::size_t intervals = std::clamp(wanted, options.min_intervals, options.max_intervals);
  const std::size_t n_ctrl = intervals + kDeg;

  std::vector<double> knots(n_ctrl + kOrder, 0.0);
  for (std::size_t k = 1; k < intervals; ++k)
    knots[kDeg + k] = static_cast<double>(k) / static_cast<double>(intervals);
  for (std::size_t k = 0; k < kOrder; ++k)
    knots[n_ctrl + k] = 1.0;

  // Smoothing grows with the noise per metre of path: for a third-derivative penalty the best
  // smoothing length scales as (sigma^2 / samples per metre)^(1/7), and the weight is its 6th
  // power.
  const double sigma_m =
      options.noise_smoothing_gain > 0.0 ? estimate_position_noise_m(points) : 0.0;
  const double noise_m3 = sigma_m * sigma_m * length / static_cast<double>(n_points);
  const double smoothing_m6 =
      options.smoothing_m6 + options.noise_smoothing_gain * std::pow(noise_m3, 6.0 / 7.0);
  // With u in [0, 1] standing for s = len * u, the penalty smoothing * integral |C_sss|^2 ds
  // becomes smoothing / len^5 * integral |C_uuu|^2 du, and the squared residuals count each
  // metre of path n / len times.
  const auto penalty_weight = [&](double len) {
    return smoothing_m6 * static_cast<double>(n_points) / std::pow(len, 6);
  };
  BandedLeastSquares ls;
  std::vector<std::size_t> order;
  std::vector<std::size_t> span_start;
  Polyline ctrl;
  ArcLengthTable arc_length;
  std::vector<SpanPoly> polys;
  solve_control_points(points, u, knots, intervals, penalty_weight(length), ls, order, span_start,
                       ctrl);

  for (int it = 0; it < options.parameter_iterations; ++it) {
    to_power_form(knots, ctrl, polys);
    // Foot points by Newton on (C(u) - P) . C'(u) = 0 from the current parameter; the ends stay
    // pinned to the ends of the curve so it spans exactly the data.
    for (std::size_t i = 1; i + 1 < n_points; ++i) {
      double ui = u[i];
      for (int newton = 0; newton < 4; ++newton) {
        const SplinePoint sp = polys[uniform_span(ui, intervals) - kDeg].derivatives(ui);
        const double rx = sp.c.x_m - points[i].x_m;
        const double ry = sp.c.y_m - points[i].y_m;
        const double speed2 = sp.d1.x_m * sp.d1.x_m + sp.d1.y_m * sp.d1.y_m;
        if (!(speed2 > 0.0)) break;
        const double g = rx * sp.d1.x_m + ry * sp.d1.y_m;
        double hess = speed2 + rx * sp.d2.x_m + ry * sp.d2.y_m;
        // Far from the curve on the concave side the Newton step can point the wrong way; the
        // Gauss-Newton step is always a descent direction.
        if (hess < 0.25 * speed2) hess = speed2;
        const double step = std::clamp(-g / hess, -0.5 / static_cast<double>(intervals),
                                       0.5 / static_cast<double>(intervals));
        ui = std::clamp(ui + step, 0.0, 1.0);
        // The refit needs the parameter to ~1e-5 of the length (0.1 mm on 10 m), and after a
        // step this small quadratic convergence has left far less.
        if (std::abs(step) < 1e-5) break;
      }
      u[i] = ui;
    }
    // Arc length position along the current curve, so the refit is parameterised by arc length
    // whatever the sampling rate or speed profile.
    arc_length.build(knots, polys);
    length = arc_length.total();
    if (!(length > 0.0)) break;
    for (std::size_t i = 1; i + 1 < n_points; ++i)
      u[i] = arc_length.at(u[i]) / length;
    solve_control_points(points, u, knots, intervals, penalty_weight(length), ls, order, span_start,
                         ctrl);
  }

  to_power_form(knots, ctrl, polys);
  arc_length.build(knots, polys);
  length = arc_length.total();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("fit_arc_length_spline: degenerate fit (zero-length curve)");
  CurveFit fit;
  fit.kind = FitKind::arc_length_spline;
  fit.domain_min = 0.0;
  fit.domain_max = length;
  for (double& k : knots)
    k *= length;
  // Keep the clamped ends exact after scaling (check() compares them for equality).
  for (std::size_t k = 0; k < kOrder; ++k)
    knots[n_ctrl + k] = length;
  fit.knots = std::move(knots);
  fit.control_points = std::move(ctrl);
  return fit;
}

CurveFit fit_curve(FitKind kind, const Polyline& points) {
  switch (kind) {
    case FitKind::poly4_xy:
      return fit_poly4(points);
    case FitKind::arc_length_spline:
      return fit_arc_length_spline(points);
  }
  throw std::invalid_argument("fit_curve: unknown FitKind");
}

double rms_distance_m(const Polyline& points, const CurveFit& fit) {
  if (points.empty()) return 0.0;
  const Polyline dense = fit.sample(std::numeric_limits<double>::infinity(), 1e-4);
  double sum = 0.0;
  for (const Point& p : points) {
    const double d = distance_to_polyline_m(p, dense);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

std::array<double, kPoly4CoefficientCount> unscaled_poly4_coefficients(const CurveFit& fit) {
  if (fit.kind != FitKind::poly4_xy || fit.coefficients.size() != kPoly4CoefficientCount)
    throw std::invalid_argument("unscaled_poly4_coefficients: not a poly4_xy fit");
  // sum_k c_k ((x - m) / s)^k expanded binomially.
  std::array<double, kPoly4CoefficientCount> out{};
  constexpr double kBinomial[5][5] = {
      {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
  for (std::size_t k = 0; k < kPoly4CoefficientCount; ++k) {
    const double ck = fit.coefficients[k] / std::pow(fit.scale, static_cast<double>(k));
    for (std::size_t j = 0; j <= k; ++j)
      out[j] += ck * kBinomial[k][j] * std::pow(-fit.center, static_cast<double>(k - j));
  }
  return out;
}

}  // namespace avk::kinematics
