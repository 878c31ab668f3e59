// Store throughput: nav ingest in batches of 1000 (target >= 200,000 samples/s) and storing one
// ~200-sample turn (target <= 1 ms), both against a WAL file database as the station runs it.

#include <benchmark/benchmark.h>

#include "support/temp_db.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using avk::testing::TempDb;

std::int64_t mission(avk::store::Store& s) {
  s.upsert_vehicle({"bench", "usim", 2.0, 1.0});
  return s.create_mission("bench", "bench", "{}");
}

void BM_NavIngestBatch1000(benchmark::State& state) {
  TempDb file("avk_bench_nav");
  avk::store::Store s(file.path());
  const auto m = mission(s);
  std::vector<avk::store::NavRow> rows(1000);
  double t_s = 0.0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      t_s += 0.1;
      rows[i] = {t_s, std::sin(t_s), std::cos(t_s), std::fmod(t_s, 360.0), 1.0, 90.0, 1.0, "turn"};
    }
    s.append_nav(m, rows);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rows.size()));
}
BENCHMARK(BM_NavIngestBatch1000)->Unit(benchmark::kMillisecond);

void BM_StoreTurn(benchmark::State& state) {
  TempDb file("avk_bench_turn");
  avk::store::Store s(file.path());
  const auto m = mission(s);
  avk::testing::ArcTurnSpec spec;
  spec.dt_s = 0.0335;  // 1 m/s over ~6.7 m: about 200 samples
  spec.position_noise_m = 0.02;
  const auto turn = avk::testing::make_arc_turn(spec);
  state.counters["samples"] = static_cast<double>(turn.samples().size());
  for (auto _ : state)
    benchmark::DoNotOptimize(s.store_turn(m, turn, avk::kinematics::TurnStatus::ok, "", 1.0));
}
BENCHMARK(BM_StoreTurn)->Unit(benchmark::kMicrosecond);

}  // namespace
