// The yaw-rate estimator's cost per navigation sample: the ConditionSet feeds it every sample at
// 10 Hz (and the harvester every sample of a log), so it must be far below a helm tick.
#include <benchmark/benchmark.h>

#include <random>

#include "kinematics/angles.hpp"
#include "kinematics/yaw_rate_estimator.hpp"

namespace {

// One sample in and the slope out, with the window full: window_s at 10 Hz.
void BM_YawRateSample(benchmark::State& state) {
  const double window_s = static_cast<double>(state.range(0));
  avk::kinematics::YawRateEstimator e(window_s);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  double t = 0.0;
  for (; t < window_s + 0.05; t += 0.1)
    e.add(t, avk::kinematics::wrap360_deg(2.0 * t + noise(rng)));
  for (auto _ : state) {
    e.add(t, avk::kinematics::wrap360_deg(2.0 * t + noise(rng)));
    benchmark::DoNotOptimize(e.rate_dps());
    t += 0.1;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_YawRateSample)->Arg(2)->Arg(5)->Arg(20);

}  // namespace
