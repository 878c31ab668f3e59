#include "kinematics/curve_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"
#include "kinematics/bspline.hpp"
#include "kinematics/fit_points.hpp"

namespace avk::kinematics {

namespace {

using namespace bspline;

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
