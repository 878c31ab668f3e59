// Store throughput: nav ingest in batches of 1000 (target >= 200,000 samples/s), storing one
// ~200-sample turn (target <= 1 ms), and building the CKT from 10,000 stored turns (target < 1 s,
// load + build; load and build are also timed alone to show which dominates), all against a WAL
// file database as the station runs it.

#include <benchmark/benchmark.h>

#include "support/temp_db.hpp"

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using avk::testing::TempDb;

std::int64_t mission(avk::store::Store& s) {
  s.vehicles().upsert({"bench", "usim", 2.0, 1.0});
  return s.missions().create("bench", "bench", "{}");
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
    s.navigation().append(m, rows);
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
    benchmark::DoNotOptimize(
        s.turns().add(m, turn, avk::kinematics::TurnStatus::ok, "", {1.0, {}, {}}));
}
BENCHMARK(BM_StoreTurn)->Unit(benchmark::kMicrosecond);

// 10,000 ok turns over the thesis' 18 cells (0.5/1.0/1.5 m/s x 10..160 deg, ~556 a cell), sampled
// at 10 Hz with 0.1 m position noise, from a vehicle whose lead-in and radius grow with speed.
// Storing them takes seconds, so the three benchmarks below share one database built on first use.
class StoredTurns {
 public:
  static StoredTurns& get() {
    static StoredTurns instance;
    return instance;
  }
  std::string path() const { return file_.path(); }
  std::size_t samples() const { return samples_; }

 private:
  StoredTurns() : file_("avk_bench_ckt") {
    avk::store::Store s(file_.path());
    const auto m = mission(s);
    constexpr double kSpeeds[] = {0.5, 1.0, 1.5};
    constexpr double kDheadings[] = {10.0, 40.0, 70.0, 100.0, 130.0, 160.0};
    for (unsigned i = 0; i < 10000; ++i) {
      const unsigned cell = i % 18;
      const double u = kSpeeds[cell / 6];
      const double d = kDheadings[cell % 6];
      avk::testing::ArcTurnSpec spec;
      spec.speed_mps = u;
      spec.dheading_deg = (i / 18) % 2 ? -d : d;
      spec.lead_in_m = 0.5 + u;
      spec.radius_m = 1.0 + 2.0 * u;
      spec.dt_s = 0.1;
      spec.position_noise_m = 0.1;
      spec.seed = i + 1;
      spec.start = {-40.0 + 7.0 * (i % 11), 25.0 - 5.0 * (i % 9), 31.0 * i};
      spec.vehicle_id = "bench";
      const auto turn = avk::testing::make_arc_turn(spec);
      samples_ += turn.samples().size();
      s.turns().add(m, turn, avk::kinematics::TurnStatus::ok, "", {2.0, {}, {}});
    }
  }
  TempDb file_;
  std::size_t samples_ = 0;
};

void BM_CktFrom10000StoredTurns(benchmark::State& state) {
  auto& data = StoredTurns::get();
  avk::store::Store s(data.path());
  for (auto _ : state) {
    const auto turns = s.turns().load_normalized({});
    benchmark::DoNotOptimize(avk::kinematics::Ckt::build(turns));
  }
  state.counters["samples"] = static_cast<double>(data.samples());
}
BENCHMARK(BM_CktFrom10000StoredTurns)->Unit(benchmark::kMillisecond);

void BM_LoadNormalized10000Turns(benchmark::State& state) {
  auto& data = StoredTurns::get();
  avk::store::Store s(data.path());
  for (auto _ : state)
    benchmark::DoNotOptimize(s.turns().load_normalized({}));
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_LoadNormalized10000Turns)->Unit(benchmark::kMillisecond);

void BM_CktBuild10000Turns(benchmark::State& state) {
  auto& data = StoredTurns::get();
  const auto turns = avk::store::Store(data.path()).turns().load_normalized({});
  for (auto _ : state)
    benchmark::DoNotOptimize(avk::kinematics::Ckt::build(turns));
}
BENCHMARK(BM_CktBuild10000Turns)->Unit(benchmark::kMillisecond);

}  // namespace
