// Simulation-error refinement of the yaw model (thesis §3.4.3: least squares minimises the
// one-step heading error, but guidance needs whole trajectories right).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::kinematics {

namespace {

Eigen::VectorXd parameters(const YawModel& m) {
  const auto n = static_cast<Eigen::Index>(m.history);
  Eigen::VectorXd t(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    t(i) = m.error_coeffs[static_cast<std::size_t>(i)];
    t(n + i) = m.heading_coeffs[static_cast<std::size_t>(i)];
  }
  return t;
}

void set_parameters(YawModel& m, const Eigen::VectorXd& t) {
  const auto n = static_cast<Eigen::Index>(m.history);
  for (Eigen::Index i = 0; i < n; ++i) {
    m.error_coeffs[static_cast<std::size_t>(i)] = t(i);
    m.heading_coeffs[static_cast<std::size_t>(i)] = t(n + i);
  }
}

struct Problem {
  const std::vector<TurnWindow>& windows;
  const RefineOptions& options;
  std::size_t residual_count() const {
    std::size_t r = 0;
    for (const auto& w : windows)
      r += w.length;
    return r;
  }

  // Weighted heading errors of every predicted sample; a diverging model gives large finite
  // residuals so the step is rejected rather than poisoning the solve.
  void residuals(const YawModel& m, Eigen::VectorXd& r) const {
    Eigen::Index i = 0;
    for (const auto& w : windows) {
      const IdentSegment& s = *w.segment;
      PredictOptions o;
      o.steps = w.length;
      const auto p = predict(m, history_at(m, s, w.start), s.desired_heading_deg[w.start],
                             {0.0, 0.0, s.heading_deg[w.start]}, 0.0, o);
      const double turn_weight =
          std::abs(w.step_deg) <= options.small_turn_deg ? options.small_turn_weight : 1.0;
      for (std::size_t j = 1; j <= w.length; ++j, ++i) {
        const double weight = turn_weight * (2 * j <= w.length ? options.first_half_weight : 1.0);
        const double d = j < p.size() ? p[j].heading_deg - s.heading_deg[w.start + j] : 1e3;
        r(i) = std::sqrt(weight) * (std::isfinite(d) ? std::clamp(d, -1e3, 1e3) : 1e3);
      }
    }
  }
};

}  // namespace

YawModel refine_yaw_model(const YawModel& start, const std::vector<TurnWindow>& windows,
                          const RefineOptions& options, RefineReport* report,
                          const std::vector<TurnWindow>& validation) {
  YawModel m = start;
  m.refined = true;
  const Problem problem{windows, options};
  const auto rows = static_cast<Eigen::Index>(problem.residual_count());
  Eigen::VectorXd theta = parameters(m);
  const Eigen::Index p = theta.size();
  Eigen::VectorXd r(rows), r_trial(rows), r_step(rows);
  problem.residuals(m, r);
  double cost = r.squaredNorm();
  if (report) *report = {0, 0, cost, cost};
  if (rows == 0) return m;
  const auto validation_error = [&](const YawModel& candidate) {
    return validation.empty() ? 0.0 : trajectory_error(candidate, validation).position_mse_m2;
  };
  Eigen::VectorXd best_theta = theta;
  double best_validation = validation_error(m);
  double mu = 1e-3;
  Eigen::MatrixXd jac(rows, p);
  YawModel trial = m;
  for (std::size_t it = 0; it < options.max_iterations; ++it) {
    // Forward differences: the model is linear in its coefficients but the prediction feeds
    // back its own headings, so the residuals are not.
    for (Eigen::Index c = 0; c < p; ++c) {
      Eigen::VectorXd t = theta;
      const double h = 1e-6 * std::max(1.0, std::abs(theta(c)));
      t(c) += h;
      set_parameters(trial, t);
      problem.residuals(trial, r_step);
      jac.col(c) = (r_step - r) / h;
    }
    const Eigen::VectorXd scale = jac.colwise().norm().transpose().cwiseMax(1e-12);
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      // Marquardt's scaled damping, solved as a stacked least-squares problem by QR.
      Eigen::MatrixXd a(rows + p, p);
      a << jac, Eigen::MatrixXd(scale.asDiagonal()) * std::sqrt(mu);
      Eigen::VectorXd b = Eigen::VectorXd::Zero(rows + p);
      b.head(rows) = -r;
      const Eigen::VectorXd delta = a.householderQr().solve(b);
      const Eigen::VectorXd candidate = theta + delta;
      set_parameters(trial, candidate);
      problem.residuals(trial, r_trial);
      const double trial_cost = r_trial.squaredNorm();
      if (std::isfinite(trial_cost) && trial_cost < cost) {
        theta = candidate;
        r = r_trial;
        const double relative = (cost - trial_cost) / cost;
        cost = trial_cost;
        mu = std::max(mu / 3.0, 1e-9);
        improved = true;
        if (report) report->iterations = it + 1;
        set_parameters(trial, theta);
        if (const double v = validation_error(trial); validation.empty() || v < best_validation) {
          best_validation = v;
          best_theta = theta;
          if (report) {
            report->best_iteration = it + 1;
            report->final_cost = cost;
          }
        }
        if (relative < 1e-6) it = options.max_iterations;
      } else {
        mu *= 4.0;
      }
    }
    if (!improved) break;
  }
  set_parameters(m, best_theta);
  return m;
}

}  // namespace avk::kinematics
