// Fit and simplification costs: a CKT of 10,000 turns is built in under a second and
// materialising a fine table fits and simplifies every cell, so these run thousands of times.
#include <benchmark/benchmark.h>

#include "kinematics/curve_fit.hpp"
#include "kinematics/simplify.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;

namespace {

// A 120-degree turn with a 2 m lead-in sampled every 0.05 m: 210 samples, 0.1 m GNSS noise.
const Polyline& turn_samples() {
  static const Polyline points = [] {
    avk::testing::ArcTurnSpec spec;
    spec.dheading_deg = 120.0;
    spec.lead_in_m = 2.0;
    spec.radius_m = 4.0;
    spec.dt_s = 0.05;
    spec.position_noise_m = 0.1;
    return avk::testing::make_arc_turn(spec).points();
  }();
  return points;
}

// The arc part only, where the thesis's y = f(x) is single valued.
const Polyline& arc_samples() {
  static const Polyline points = [] {
    Polyline out;
    for (const Point& p : turn_samples())
      if (p.y_m > 2.0) out.push_back(p);
    return out;
  }();
  return points;
}

void BM_FitPoly4(benchmark::State& state) {
  const Polyline& points = arc_samples();
  for (auto _ : state)
    benchmark::DoNotOptimize(fit_poly4(points));
  state.counters["samples"] = static_cast<double>(points.size());
}
BENCHMARK(BM_FitPoly4);

void BM_FitArcLengthSpline(benchmark::State& state) {
  const Polyline& points = turn_samples();
  for (auto _ : state)
    benchmark::DoNotOptimize(fit_arc_length_spline(points));
  state.counters["samples"] = static_cast<double>(points.size());
}
BENCHMARK(BM_FitArcLengthSpline);

void BM_SampleSpline(benchmark::State& state) {
  const CurveFit fit = fit_arc_length_spline(turn_samples());
  std::size_t n = 0;
  for (auto _ : state) {
    const Polyline line = fit.sample(0.1);
    n = line.size();
    benchmark::DoNotOptimize(line.data());
  }
  state.counters["points"] = static_cast<double>(n);
}
BENCHMARK(BM_SampleSpline);

void BM_PiecewiseLinear(benchmark::State& state) {
  const CurveFit fit = fit_arc_length_spline(turn_samples());
  std::size_t n = 0;
  for (auto _ : state) {
    const Polyline line = piecewise_linear(fit, 0.05);
    n = line.size();
    benchmark::DoNotOptimize(line.data());
  }
  state.counters["vertices"] = static_cast<double>(n);
}
BENCHMARK(BM_PiecewiseLinear);

void BM_SimplifyPolyline(benchmark::State& state) {
  avk::testing::ArcTurnSpec spec;
  spec.dheading_deg = 170.0;
  spec.lead_in_m = 5.0;
  spec.radius_m = 10.0;
  spec.tail_m = 5.0;
  spec.position_noise_m = 0.02;
  spec.dt_s = (spec.lead_in_m + spec.radius_m * 2.967 + spec.tail_m) / 1999.0;
  const Polyline dense = avk::testing::make_arc_turn(spec).points();
  std::size_t n = 0;
  for (auto _ : state) {
    const Polyline line = simplify_polyline(dense, 0.05);
    n = line.size();
    benchmark::DoNotOptimize(line.data());
  }
  state.counters["input"] = static_cast<double>(dense.size());
  state.counters["vertices"] = static_cast<double>(n);
}
BENCHMARK(BM_SimplifyPolyline);

}  // namespace
