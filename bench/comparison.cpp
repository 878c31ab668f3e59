// The prediction comparison: the thesis' in-sample scoring (Figures 5-7/5-8) and the fair
// leave-one-out one, over every cell of the thesis' Figure 4-1 grid; target < 100 ms for 18 cells.
#include <benchmark/benchmark.h>

#include <cmath>

#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/predictive_comparison.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;

namespace {

// 3 speeds x 6 heading changes, 5 turns a cell at 10 Hz with 0.1 m GNSS and 1 deg heading noise.
const Ckt& thesis_table() {
  static const Ckt table = Ckt::build(avk::testing::thesis_grid_turns(5, 0.1, 0.1, 1.0));
  return table;
}

// A cheap stand-in for the black-box model: an arc a little off the vehicle's own (lead-in
// 0.5 + u, radius 1 + 2u), sampled at 10 Hz like a simulated prediction.
Polyline arc_prediction(double speed_mps, double dheading_deg) {
  avk::testing::ArcTurnSpec s;
  s.speed_mps = speed_mps;
  s.dheading_deg = dheading_deg;
  s.lead_in_m = 0.4 + speed_mps;
  s.radius_m = 1.2 + 1.8 * speed_mps;
  const double total = avk::testing::arc_turn_length_m(s);
  const double step = 0.1 * speed_mps;
  Polyline out;
  const auto n = static_cast<int>(std::ceil(total / step));
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k)
    out.push_back(avk::testing::arc_turn_point(s, std::min(total, k * step), nullptr));
  return out;
}

void BM_CompareThesisGrid(benchmark::State& state) {
  const Ckt& table = thesis_table();
  const TurnPredictor model = arc_prediction;
  for (auto _ : state) {
    auto cells = compare_predictions(table, &model);
    benchmark::DoNotOptimize(cells.data());
  }
}
BENCHMARK(BM_CompareThesisGrid)->Unit(benchmark::kMillisecond);

void BM_CompareThesisGridNoModel(benchmark::State& state) {
  const Ckt& table = thesis_table();
  for (auto _ : state) {
    auto cells = compare_predictions(table, nullptr);
    benchmark::DoNotOptimize(cells.data());
  }
}
BENCHMARK(BM_CompareThesisGridNoModel)->Unit(benchmark::kMillisecond);

// The fair comparison of `avk compare`: every turn of the 18 cells held out in turn (AVK from the
// other four), both metrics for three methods, and the corridor's coverage. Target < 100 ms.
void BM_ComparePredictiveThesisGrid(benchmark::State& state) {
  const Ckt& table = thesis_table();
  const TurnPredictor model = arc_prediction;
  for (auto _ : state) {
    auto cells = compare_predictive(table, &model);
    benchmark::DoNotOptimize(cells.data());
  }
}
BENCHMARK(BM_ComparePredictiveThesisGrid)->Unit(benchmark::kMillisecond);

}  // namespace
