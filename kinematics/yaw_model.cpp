#include "kinematics/yaw_model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

const char* to_string(YawModelForm f) {
  return f == YawModelForm::thesis ? "thesis" : "invariant";
}

std::optional<YawModelForm> yaw_model_form_from_string(const std::string& s) {
  if (s == "thesis") return YawModelForm::thesis;
  if (s == "invariant") return YawModelForm::invariant;
  return std::nullopt;
}

namespace {

// The regressor row for predicting sample k+1 from headings psi[..k] and errors e[..k].
template <typename Row>
void regressors(YawModelForm form, std::size_t n, const double* psi, const double* e, std::size_t k,
                Row&& row) {
  for (std::size_t i = 0; i < n; ++i)
    row(i) = e[k - i];
  for (std::size_t i = 0; i < n; ++i)
    row(n + i) = form == YawModelForm::thesis ? psi[k - i] : psi[k - i] - psi[k - i - 1];
}

double next_heading(const YawModel& m, const double* psi, const double* e, std::size_t k) {
  const std::size_t n = m.history;
  double v = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    v += m.error_coeffs[i] * e[k - i];
  if (m.form == YawModelForm::thesis) {
    for (std::size_t i = 0; i < n; ++i)
      v += m.heading_coeffs[i] * psi[k - i];
    return v;
  }
  for (std::size_t i = 0; i < n; ++i)
    v += m.heading_coeffs[i] * (psi[k - i] - psi[k - i - 1]);
  return psi[k] + v;
}

void check_model(const YawModel& m) {
  if (m.history == 0 || m.error_coeffs.size() != m.history ||
      m.heading_coeffs.size() != m.history || !(m.rate_hz > 0.0)) {
    throw std::invalid_argument("yaw model: " + std::to_string(m.error_coeffs.size()) + " + " +
                                std::to_string(m.heading_coeffs.size()) +
                                " coefficients do not match a history of " +
                                std::to_string(m.history));
  }
}

}  // namespace

YawHistory steady_history(const YawModel& m, double course_deg) {
  return {std::vector<double>(m.warmup(), course_deg), std::vector<double>(m.warmup(), course_deg)};
}

YawHistory turning_history(const YawModel& m, double course_deg, double yaw_rate_dps) {
  check_model(m);
  const std::size_t n = m.warmup();
  const double step = yaw_rate_dps * m.dt_s();
  YawHistory h{std::vector<double>(n), std::vector<double>(n)};
  for (std::size_t j = 0; j < n; ++j)
    h.heading_deg[j] = course_deg - step * static_cast<double>(n - 1 - j);
  double a_sum = 0.0;
  for (double a : m.error_coeffs)
    a_sum += a;
  // With a constant error e the next heading is linear in e: psi(k+1) = rest + a_sum e. Choose e
  // so that psi(k+1) - psi(k) = step.
  double rest = 0.0;
  const std::size_t k = n - 1;
  for (std::size_t i = 0; i < m.heading_coeffs.size(); ++i) {
    rest += m.form == YawModelForm::thesis
                ? m.heading_coeffs[i] * h.heading_deg[k - i]
                : m.heading_coeffs[i] * (h.heading_deg[k - i] - h.heading_deg[k - i - 1]);
  }
  const double wanted = m.form == YawModelForm::thesis ? course_deg + step : step;
  if (std::abs(a_sum) < 1e-12) {
    throw std::invalid_argument("turning_history: the model's error coefficients sum to zero");
  }
  const double e = (wanted - rest) / a_sum;
  for (std::size_t j = 0; j < n; ++j)
    h.desired_heading_deg[j] = h.heading_deg[j] + e;
  return h;
}

YawHistory history_at(const YawModel& m, const IdentSegment& s, std::size_t k) {
  if (k + 1 < m.warmup() || k >= s.size())
    throw std::invalid_argument("history_at: sample " + std::to_string(k) + " has no full history");
  const std::size_t first = k + 1 - m.warmup();
  return {std::vector<double>(s.heading_deg.begin() + first, s.heading_deg.begin() + k + 1),
          std::vector<double>(s.desired_heading_deg.begin() + first,
                              s.desired_heading_deg.begin() + k + 1)};
}

std::vector<PredictedStep> predict(const YawModel& m, const YawHistory& history, double desired_deg,
                                   Pose start, double speed_mps, const PredictOptions& options) {
  check_model(m);
  if (history.heading_deg.size() != m.warmup() ||
      history.desired_heading_deg.size() != m.warmup()) {
    throw std::invalid_argument("predict: the history needs " + std::to_string(m.warmup()) +
                                " samples");
  }
  std::vector<double> psi = history.heading_deg;
  std::vector<double> e(psi.size());
  for (std::size_t i = 0; i + 1 < psi.size(); ++i)
    e[i] = angle180_deg(history.desired_heading_deg[i] - psi[i]);
  // The prediction starts where the desired heading has just changed (thesis §3.4.2).
  e.back() = angle180_deg(desired_deg - psi.back());
  psi.reserve(psi.size() + options.steps + 1);
  e.reserve(psi.capacity());

  std::vector<PredictedStep> out;
  out.reserve(options.steps + 1);
  const double dt = m.dt_s();
  double x = start.x_m, y = start.y_m, u = speed_mps;
  // Positions follow the history's heading frame shifted to the start pose's heading.
  const double offset = start.heading_deg - psi.back();
  out.push_back({0.0, x, y, psi.back(), u});
  const double target_speed = options.desired_speed_mps > 0.0 ? options.desired_speed_mps : u;
  for (std::size_t step = 1; step <= options.steps; ++step) {
    const std::size_t k = psi.size() - 1;
    const double heading = deg_to_rad(psi[k] + offset);
    x += u * dt * std::sin(heading);
    y += u * dt * std::cos(heading);
    const double next = next_heading(m, psi.data(), e.data(), k);
    if (options.use_speed_model && m.speed) {
      const auto& s = *m.speed;
      u = std::max(0.0, u + s.gain * (target_speed - u) - s.sag_per_deg * std::abs(next - psi[k]) +
                            s.bias_mps);
    }
    psi.push_back(next);
    e.push_back(angle180_deg(desired_deg - next));
    out.push_back({static_cast<double>(step) * dt, x, y, next, u});
    if (!std::isfinite(next)) break;
    if (options.completion_threshold_deg > 0.0 &&
        std::abs(e.back()) <= options.completion_threshold_deg) {
      break;
    }
  }
  return out;
}

Polyline predict_normalized_turn(const YawModel& m, double speed_mps, double dheading_deg,
                                 double completion_threshold_deg, double course_deg,
                                 std::size_t max_steps, bool use_speed_model,
                                 double initial_yaw_rate_dps,
                                 std::optional<double> speed_after_mps) {
  // Into the turn is clockwise for a right turn, anticlockwise for a left one.
  const double raw_rate_dps = dheading_deg < 0.0 ? -initial_yaw_rate_dps : initial_yaw_rate_dps;
  const YawHistory h = initial_yaw_rate_dps == 0.0 ? steady_history(m, course_deg)
                                                   : turning_history(m, course_deg, raw_rate_dps);
  PredictOptions o;
  o.steps = max_steps;
  o.completion_threshold_deg = completion_threshold_deg;
  o.use_speed_model = use_speed_model;
  o.desired_speed_mps = speed_after_mps.value_or(speed_mps);
  const Pose start{0.0, 0.0, course_deg};
  const auto steps = predict(m, h, course_deg + dheading_deg, start, speed_mps, o);
  Polyline out;
  out.reserve(steps.size());
  const TurnSide side = side_of(dheading_deg);
  for (const auto& s : steps)
    out.push_back(normalize_point({s.x_m, s.y_m}, start, side));
  return out;
}

// --- identification -----------------------------------------------------------------------

namespace {

// The stacked regression reduced to what least squares needs: R (p x p, upper triangular), Q'y
// (p), |X|^2 and the number of equations. Computed block by block, a QR of the running triangle
// on top of each block of rows, so the design matrix, which grows with the data (a long campaign
// gives hundreds of thousands of rows), is never held whole. It equals one QR of the whole
// matrix up to the signs of R's rows (with Q'y's), which the least-squares solution does not see.
struct ReducedRegression {
  Eigen::MatrixXd r;
  Eigen::VectorXd qty;
  double x_squared_norm = 0.0;
  Eigen::Index rows = 0;
};

ReducedRegression reduce(const std::vector<IdentSegment>& segments, YawModelForm form,
                         std::size_t n) {
  const std::size_t warm = form == YawModelForm::thesis ? n : n + 1;
  const auto p = static_cast<Eigen::Index>(2 * n);
  constexpr Eigen::Index kBlock = 4096;
  // [X y] rows: the running triangle (at most p + 1 rows) on top, then the block being filled.
  Eigen::MatrixXd work(p + 1 + kBlock, p + 1);
  Eigen::Index top = 0;
  Eigen::Index filled = 0;
  ReducedRegression out;
  const auto fold = [&] {
    if (filled == 0) return;
    const Eigen::Index m = top + filled;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(work.topRows(m));
    top = std::min(m, p + 1);
    work.topRows(top) = qr.matrixQR().topRows(top).triangularView<Eigen::Upper>();
    filled = 0;
  };
  std::vector<double> e;
  for (const auto& s : segments) {
    if (s.size() <= warm) continue;
    e.resize(s.size());
    for (std::size_t k = 0; k < s.size(); ++k)
      e[k] = s.error_deg(k);
    for (std::size_t k = warm - 1; k + 1 < s.size(); ++k) {
      const Eigen::Index row = top + filled;
      regressors(form, n, s.heading_deg.data(), e.data(), k,
                 [&](std::size_t c) -> double& { return work(row, static_cast<Eigen::Index>(c)); });
      work(row, p) = form == YawModelForm::thesis ? s.heading_deg[k + 1]
                                                  : s.heading_deg[k + 1] - s.heading_deg[k];
      out.x_squared_norm += work.row(row).head(p).squaredNorm();
      ++out.rows;
      if (++filled == kBlock) fold();
    }
  }
  fold();
  if (out.rows >= p) {
    out.r = work.topLeftCorner(p, p).triangularView<Eigen::Upper>();
    out.qty = work.col(p).head(p);
  }
  return out;
}

YawModel model_from(const FitOptions& o, double rate_hz, const Eigen::VectorXd& theta,
                    double lambda) {
  YawModel m;
  m.form = o.form;
  m.history = o.history;
  m.rate_hz = rate_hz;
  m.ridge_lambda = lambda;
  const auto n = static_cast<Eigen::Index>(o.history);
  m.error_coeffs.assign(theta.data(), theta.data() + n);
  m.heading_coeffs.assign(theta.data() + n, theta.data() + 2 * n);
  return m;
}

}  // namespace

YawModel fit_yaw_model(const std::vector<IdentSegment>& training, const FitOptions& options,
                       const std::vector<IdentSegment>& validation) {
  if (options.history == 0) throw std::invalid_argument("fit: history must be at least 1 sample");
  if (training.empty()) throw std::invalid_argument("fit: no training data");
  const double rate = 1.0 / training.front().dt_s;
  for (const auto& s : training)
    if (std::abs(s.dt_s - training.front().dt_s) > 1e-12)
      throw std::invalid_argument("fit: training segments have different sample rates");
  const ReducedRegression r = reduce(training, options.form, options.history);
  const auto p = static_cast<Eigen::Index>(2 * options.history);
  if (r.rows < p)
    throw std::invalid_argument("fit: " + std::to_string(r.rows) + " equations for " +
                                std::to_string(p) + " coefficients: too little data for " +
                                std::to_string(options.history) + " samples of history");
  // Every ridge strength is then a small p x p problem, since |X t - y|^2 = |R t - Q'y|^2 +
  // const.
  const Eigen::MatrixXd& rr = r.r;
  const Eigen::VectorXd& qty = r.qty;
  const double scale = r.x_squared_norm / static_cast<double>(p);
  const auto solve = [&](double lambda_rel) {
    Eigen::MatrixXd a(2 * p, p);
    a << rr, Eigen::MatrixXd::Identity(p, p) * std::sqrt(lambda_rel * scale);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * p);
    b.head(p) = qty;
    return Eigen::VectorXd(a.colPivHouseholderQr().solve(b));
  };
  if (options.ridge_lambda)
    return model_from(options, rate, solve(*options.ridge_lambda), *options.ridge_lambda);

  const YawModel probe = model_from(options, rate, Eigen::VectorXd::Zero(p), 0.0);
  const auto windows = turn_windows(validation, probe.warmup());
  if (windows.empty()) return model_from(options, rate, solve(0.0), 0.0);
  YawModel best;
  double best_error = std::numeric_limits<double>::infinity();
  for (double lambda : {0.0, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1}) {
    YawModel m = model_from(options, rate, solve(lambda), lambda);
    const double err = trajectory_error(m, windows).position_mse_m2;
    if (err < best_error) {
      best_error = err;
      best = std::move(m);
    }
  }
  if (!std::isfinite(best_error)) return model_from(options, rate, solve(0.0), 0.0);
  return best;
}

std::optional<SpeedModel> fit_speed_model(const std::vector<IdentSegment>& segments) {
  std::size_t rows = 0;
  for (const auto& s : segments)
    if (!s.desired_speed_mps.empty() && s.size() > 2) rows += s.size() - 2;
  if (rows < 3) return std::nullopt;
  Eigen::MatrixXd x(static_cast<Eigen::Index>(rows), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows));
  Eigen::Index row = 0;
  for (const auto& s : segments) {
    if (s.desired_speed_mps.empty() || s.size() <= 2) continue;
    for (std::size_t k = 1; k + 1 < s.size(); ++k, ++row) {
      x(row, 0) = s.desired_speed_mps[k] - s.speed_mps[k];
      x(row, 1) = -std::abs(s.heading_deg[k + 1] - s.heading_deg[k]);
      x(row, 2) = 1.0;
      y(row) = s.speed_mps[k + 1] - s.speed_mps[k];
    }
  }
  const Eigen::Vector3d t = x.colPivHouseholderQr().solve(y);
  return SpeedModel{t(0), t(1), t(2)};
}

std::vector<TurnWindow> turn_windows(const std::vector<IdentSegment>& segments, std::size_t warmup,
                                     double min_step_deg, double max_length_s) {
  // Interpolation may spread one step of the guidance over two samples: a step is a run of
  // changing samples, and the window starts at its last one, once the new value holds.
  constexpr double kChange_deg = 0.5;
  std::vector<TurnWindow> out;
  for (const auto& s : segments) {
    const auto& d = s.desired_heading_deg;
    const auto max_len = static_cast<std::size_t>(std::floor(max_length_s / s.dt_s));
    const auto changes = [&](std::size_t k) {
      return k > 0 && k < d.size() && std::abs(d[k] - d[k - 1]) >= kChange_deg;
    };
    for (std::size_t k = 1; k < s.size(); ++k) {
      if (!changes(k) || changes(k + 1)) continue;
      std::size_t j = k;
      while (j > 1 && changes(j - 1))
        --j;
      const double step = d[k] - d[j - 1];
      if (std::abs(step) < min_step_deg || k + 1 < warmup) continue;
      std::size_t len = 0;
      while (k + len + 1 < s.size() && len < max_len && !changes(k + len + 1))
        ++len;
      if (len >= 4) out.push_back({&s, k, len, step});
    }
  }
  return out;
}

TrajectoryError trajectory_error(const YawModel& m, const std::vector<TurnWindow>& windows,
                                 bool use_speed_model) {
  TrajectoryError te;
  double pos = 0.0, head = 0.0;
  std::size_t points = 0;
  for (const auto& w : windows) {
    const IdentSegment& s = *w.segment;
    PredictOptions o;
    o.steps = w.length;
    o.use_speed_model = use_speed_model;
    if (!s.desired_speed_mps.empty()) o.desired_speed_mps = s.desired_speed_mps[w.start];
    const auto p =
        predict(m, history_at(m, s, w.start), s.desired_heading_deg[w.start],
                {s.x_m[w.start], s.y_m[w.start], s.heading_deg[w.start]}, s.speed_mps[w.start], o);
    for (std::size_t j = 1; j < p.size(); ++j) {
      const std::size_t k = w.start + j;
      const double dx = p[j].x_m - s.x_m[k], dy = p[j].y_m - s.y_m[k];
      const double dh = p[j].heading_deg - s.heading_deg[k];
      pos += dx * dx + dy * dy;
      head += dh * dh;
      ++points;
    }
    ++te.windows;
  }
  if (points) {
    te.position_mse_m2 = pos / static_cast<double>(points);
    te.heading_rms_deg = std::sqrt(head / static_cast<double>(points));
  }
  return te;
}

double one_step_rms_deg(const YawModel& m, const std::vector<IdentSegment>& segments) {
  check_model(m);
  double sum = 0.0;
  std::size_t count = 0;
  std::vector<double> e;
  for (const auto& s : segments) {
    if (s.size() <= m.warmup()) continue;
    e.resize(s.size());
    for (std::size_t k = 0; k < s.size(); ++k)
      e[k] = s.error_deg(k);
    for (std::size_t k = m.warmup() - 1; k + 1 < s.size(); ++k) {
      const double d = next_heading(m, s.heading_deg.data(), e.data(), k) - s.heading_deg[k + 1];
      sum += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

}  // namespace avk::kinematics
