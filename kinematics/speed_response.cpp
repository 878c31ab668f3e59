#include "kinematics/speed_response.hpp"

#include <algorithm>
#include <cmath>

namespace avk::kinematics {

namespace {

// The time constant of 1 - exp(-t / tau) closest (least squares) to the samples: a search over a
// logarithmic grid, refined once around the best.
double fit_first_order_tau_s(const std::vector<double>& fraction, double dt_s) {
  const auto sse = [&](double tau) {
    double e = 0.0;
    for (std::size_t k = 0; k < fraction.size(); ++k) {
      const double d = fraction[k] - (1.0 - std::exp(-static_cast<double>(k) * dt_s / tau));
      e += d * d;
    }
    return e;
  };
  double best = 1.0, best_e = sse(1.0);
  for (double step : {1.1, 1.01}) {
    const double centre = best;
    for (int i = -60; i <= 60; ++i) {
      const double tau = std::clamp(centre * std::pow(step, static_cast<double>(i)), 0.05, 1000.0);
      const double e = sse(tau);
      if (e < best_e) {
        best = tau;
        best_e = e;
      }
    }
  }
  return best;
}

}  // namespace

double SpeedResponse::fraction_at(double t_s) const {
  if (fraction.empty() || !(t_s > 0.0)) return 0.0;
  const double end_s = dt_s * static_cast<double>(fraction.size() - 1);
  if (t_s >= end_s) {
    const double rest = 1.0 - fraction.back();
    return 1.0 - rest * std::exp(-(t_s - end_s) / tail_tau_s);
  }
  const double k = t_s / dt_s;
  const std::size_t i = static_cast<std::size_t>(std::floor(k));
  const double w = k - static_cast<double>(i);
  return (1.0 - w) * fraction[i] + w * fraction[std::min(i + 1, fraction.size() - 1)];
}

SpeedResponse first_order_speed_response(double tau_s, double dt_s) {
  SpeedResponse r;
  r.dt_s = dt_s;
  r.tail_tau_s = tau_s;
  r.fraction = {0.0};
  return r;
}

std::optional<SpeedResponse> speed_response_of_model(const YawModel& model) {
  if (!model.speed || !(model.speed->gain > 0.0 && model.speed->gain <= 1.0)) return std::nullopt;
  const double g = model.speed->gain;
  // phi(k dt) = 1 - (1 - g)^k: first order with tau = -dt / ln(1 - g) (instant for g = 1).
  const double tau = g >= 1.0 ? 1e-6 : -model.dt_s() / std::log(1.0 - g);
  return first_order_speed_response(tau, model.dt_s());
}

std::optional<SpeedResponse> measured_speed_response(const std::vector<TurnSequence>& turns,
                                                     double dt_s) {
  std::vector<const TurnSequence*> used;
  double window_s = 0.0;
  for (const auto& t : turns) {
    const TurnMeta& m = t.meta();
    if (m.status != TurnStatus::ok || !m.speed_after_mps || t.samples().size() < 2) continue;
    if (std::abs(*m.speed_after_mps - m.commanded_speed_mps) < 1e-6) continue;
    const double d = t.samples().back().t_s - t.samples().front().t_s;
    window_s = used.empty() ? d : std::min(window_s, d);
    used.push_back(&t);
  }
  if (used.empty() || !(window_s > dt_s)) return std::nullopt;
  SpeedResponse r;
  r.dt_s = dt_s;
  r.n_turns = used.size();
  const std::size_t n = static_cast<std::size_t>(std::floor(window_s / dt_s)) + 1;
  r.fraction.assign(n, 0.0);
  for (const TurnSequence* t : used) {
    const auto& s = t->samples();
    const double change = *t->meta().speed_after_mps - t->meta().commanded_speed_mps;
    const double t0 = s.front().t_s, u_start = s.front().speed_mps;
    std::size_t j = 0;
    for (std::size_t k = 1; k < n; ++k) {
      const double tk = t0 + static_cast<double>(k) * dt_s;
      while (j + 2 < s.size() && s[j + 1].t_s < tk)
        ++j;
      const double span = s[j + 1].t_s - s[j].t_s;
      const double w = span > 0.0 ? std::clamp((tk - s[j].t_s) / span, 0.0, 1.0) : 0.0;
      const double u = (1.0 - w) * s[j].speed_mps + w * s[j + 1].speed_mps;
      r.fraction[k] += (u - u_start) / change / static_cast<double>(used.size());
    }
  }
  r.fraction[0] = 0.0;
  r.tail_tau_s = fit_first_order_tau_s(r.fraction, dt_s);
  return r;
}

}  // namespace avk::kinematics
