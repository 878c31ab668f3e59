// Black-box yaw model: fitting n = 40 on one hour of 4 Hz data (target < 50 ms) and predicting
// one 30 s trajectory (target < 50 us).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/yaw_model.hpp"

namespace {

using namespace avk::kinematics;

// One hour of a first-order heading loop under random desired-heading steps, with compass noise.
IdentSegment hour_of_data() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> step(-120.0, 120.0);
  std::uniform_int_distribution<int> hold(12, 40);
  std::normal_distribution<double> noise(0.0, 0.5);
  IdentSegment s;
  s.dt_s = 0.25;
  double psi = 0.0, rate = 0.0, desired = 0.0, x = 0.0, y = 0.0;
  int left = 0;
  for (int k = 0; k < 4 * 3600; ++k) {
    if (--left <= 0) {
      desired += step(rng);
      left = hold(rng);
    }
    rate += 0.25 * (std::clamp(0.8 * angle180_deg(desired - psi), -20.0, 20.0) - rate);
    psi += rate * s.dt_s;
    x += 1.5 * s.dt_s * std::sin(deg_to_rad(psi));
    y += 1.5 * s.dt_s * std::cos(deg_to_rad(psi));
    s.heading_deg.push_back(psi + noise(rng));
    s.desired_heading_deg.push_back(desired);
    s.x_m.push_back(x);
    s.y_m.push_back(y);
    s.speed_mps.push_back(1.5);
  }
  return s;
}

void BM_FitN40OneHour(benchmark::State& state) {
  const std::vector<IdentSegment> data = {hour_of_data()};
  for (auto _ : state)
    benchmark::DoNotOptimize(fit_yaw_model(data, {YawModelForm::invariant, 40, 0.0}));
  state.counters["samples"] = static_cast<double>(data.front().size());
}
BENCHMARK(BM_FitN40OneHour)->Unit(benchmark::kMillisecond);

void BM_Predict30s(benchmark::State& state) {
  const YawModel m = fit_yaw_model({hour_of_data()}, {YawModelForm::invariant, 40, 0.0});
  const YawHistory h = steady_history(m, 30.0);
  PredictOptions o;
  o.steps = 120;
  for (auto _ : state)
    benchmark::DoNotOptimize(predict(m, h, 100.0, {0.0, 0.0, 30.0}, 1.5, o));
}
BENCHMARK(BM_Predict30s)->Unit(benchmark::kMicrosecond);

}  // namespace
