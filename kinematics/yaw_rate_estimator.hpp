#pragma once
// Yaw rate from compass headings, fit for a real compass: the least-squares slope of the
// (unwrapped) heading over a trailing time window.
//
// The thesis differenced consecutive headings and averaged n of the differences (eqs. 4.1, 4.2).
// That average telescopes to (ψ_k − ψ_{k−n}) / (t_k − t_{k−n}): only the two end samples count,
// so with a compass of noise σ at 10 Hz and n = 5 it scatters by √2 σ / 0.5 s ≈ 2.8 °/s for
// σ = 1°, nearly three times a 1 °/s steady-course limit. The least-squares slope uses every
// sample of the window; for samples at times t_i with white heading noise σ its standard
// deviation is
//     σ_rate = σ / sqrt(Σ (t_i − t̄)²),
// which for n equally spaced samples dt apart is σ / (dt sqrt(n (n² − 1) / 12)): 0.36 °/s for
// σ = 1° over 2 s at 10 Hz (n = 21). A constant rate is estimated without bias; a rate that
// changes is seen as its average over the window, about window / 2 late.

#include <cstddef>
#include <deque>
#include <optional>

namespace avk::kinematics {

class YawRateEstimator {
 public:
  // window_s > 0: the trailing span of samples the slope is fitted over.
  explicit YawRateEstimator(double window_s);

  // One compass heading (degrees, any range; unwrapped against the previous one). A sample not
  // later than the previous one is ignored: a slope needs distinct times.
  void add(double t_s, double heading_deg);
  void reset();

  // The slope in °/s (+ clockwise), once the samples span the whole window; empty before.
  std::optional<double> rate_dps() const;
  // The slope's standard deviation for white heading noise of heading_sigma_deg at the present
  // sample times (the formula above); empty when rate_dps() is.
  std::optional<double> noise_sd_dps(double heading_sigma_deg) const;

  double window_s() const { return window_s_; }
  std::size_t sample_count() const { return samples_.size(); }

 private:
  struct Sample {
    double t_s;
    double heading_deg;  // unwrapped
  };
  struct Fit {
    double slope_dps;
    double spread_s2;  // Σ (t_i − t̄)²
  };
  // The least-squares line through the window, once it is full and its times are distinct.
  std::optional<Fit> fit() const;

  double window_s_;
  std::deque<Sample> samples_;
  std::optional<double> first_t_s_;  // the oldest sample since the last reset
};

// The analytic standard deviation of the least-squares slope over n samples dt_s apart with
// white heading noise heading_sigma_deg: σ / (dt sqrt(n (n² − 1) / 12)). n >= 2, dt_s > 0.
double least_squares_rate_sd_dps(double heading_sigma_deg, double dt_s, std::size_t n);

}  // namespace avk::kinematics
