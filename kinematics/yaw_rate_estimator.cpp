#include "kinematics/yaw_rate_estimator.hpp"

#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

namespace {
// Sample times are floating-point sums of a period: a window of 2.0 s at 10 Hz must count as
// spanned by samples 1.9999999 s apart.
constexpr double kTimeSlack_s = 1e-6;
}  // namespace

YawRateEstimator::YawRateEstimator(double window_s) : window_s_(window_s) {
  if (!(window_s > 0.0) || !std::isfinite(window_s))
    throw std::invalid_argument("yaw-rate window must be a positive number of seconds");
}

void YawRateEstimator::reset() {
  samples_.clear();
  first_t_s_.reset();
}

void YawRateEstimator::add(double t_s, double heading_deg) {
  if (!std::isfinite(t_s) || !std::isfinite(heading_deg)) return;
  if (!samples_.empty() && t_s <= samples_.back().t_s) return;
  const double unwrapped =
      samples_.empty()
          ? heading_deg
          : samples_.back().heading_deg + angle180_deg(heading_deg - samples_.back().heading_deg);
  samples_.push_back({t_s, unwrapped});
  if (!first_t_s_) first_t_s_ = t_s;
  // Keep exactly the samples in [t − window, t].
  while (samples_.front().t_s < t_s - window_s_ - kTimeSlack_s)
    samples_.pop_front();
}

std::optional<YawRateEstimator::Fit> YawRateEstimator::fit() const {
  if (samples_.size() < 2 || !first_t_s_ ||
      samples_.back().t_s - *first_t_s_ < window_s_ - kTimeSlack_s)
    return std::nullopt;
  // Centred on the newest sample, so the sums stay small whatever the clock and heading.
  const double t0 = samples_.back().t_s, h0 = samples_.back().heading_deg;
  const double n = static_cast<double>(samples_.size());
  double st = 0.0, sh = 0.0;
  for (const Sample& s : samples_) {
    st += s.t_s - t0;
    sh += s.heading_deg - h0;
  }
  const double mean_t = st / n, mean_h = sh / n;
  double sxx = 0.0, sxy = 0.0;
  for (const Sample& s : samples_) {
    const double dt = s.t_s - t0 - mean_t;
    sxx += dt * dt;
    sxy += dt * (s.heading_deg - h0 - mean_h);
  }
  if (!(sxx > 0.0)) return std::nullopt;
  return Fit{sxy / sxx, sxx};
}

std::optional<double> YawRateEstimator::rate_dps() const {
  const auto f = fit();
  if (!f) return std::nullopt;
  return f->slope_dps;
}

std::optional<double> YawRateEstimator::noise_sd_dps(double heading_sigma_deg) const {
  const auto f = fit();
  if (!f) return std::nullopt;
  return heading_sigma_deg / std::sqrt(f->spread_s2);
}

double least_squares_rate_sd_dps(double heading_sigma_deg, double dt_s, std::size_t n) {
  if (n < 2 || !(dt_s > 0.0))
    throw std::invalid_argument("a slope needs at least two samples a positive time apart");
  const double nn = static_cast<double>(n);
  return heading_sigma_deg / (dt_s * std::sqrt(nn * (nn * nn - 1.0) / 12.0));
}

}  // namespace avk::kinematics
