// The arc length spline fit of kinematics/curve_fit.hpp: samples are placed by chord length, then
// by their foot points on the last curve, and control points solved by banded least squares with
// a jerk penalty.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/bspline.hpp"
#include "kinematics/curve_fit.hpp"
#include "kinematics/fit_points.hpp"
#include "kinematics/median.hpp"

namespace avk::kinematics {

namespace {

using namespace bspline;

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
  const double median = upper_median(d3);
  // Each coordinate of the third difference has variance (1 + 9 + 9 + 1) sigma^2, so its norm is
  // Rayleigh with scale sqrt(20) sigma and median sqrt(20) * sqrt(2 ln 2) sigma.
  return median / (std::sqrt(20.0) * std::sqrt(2.0 * std::log(2.0)));
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

}  // namespace avk::kinematics
