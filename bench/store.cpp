// Store throughput on both engines (argument 0: an SQLite WAL file as the station runs it; 1: a
// PostgreSQL database of a throwaway local cluster, over its Unix socket, fsync off as in the
// tests): nav ingest in batches of 1000 (target >= 200,000 samples/s), storing one ~200-sample
// turn (target <= 1 ms), a Figure 4-1 mission as the recorder writes it, three stations writing
// turns at once, and building the CKT from 10,000 stored turns (target < 1 s, load + build; load
// and build are also timed alone to show which dominates).

#include <benchmark/benchmark.h>

#include "support/pg_cluster.hpp"
#include "support/temp_db.hpp"

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "kinematics/ckt.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

namespace {

using avk::testing::TempDb;

// A fresh database of the engine the benchmark's argument names.
class BenchDb {
 public:
  BenchDb(std::int64_t engine, const std::string& stem) {
    if (engine == 0)
      file_ = std::make_unique<TempDb>(stem);
    else
      pg_ = std::make_unique<avk::testing::PgTestDb>();
  }
  std::string path() const { return file_ ? file_->path() : pg_->conninfo(); }

 private:
  std::unique_ptr<TempDb> file_;
  std::unique_ptr<avk::testing::PgTestDb> pg_;
};

void label(benchmark::State& state) {
  state.SetLabel(state.range(0) == 0 ? "sqlite" : "postgresql");
}

std::int64_t mission(avk::store::Store& s) {
  s.vehicles().upsert({"bench", "usim", 2.0, 1.0});
  return s.missions().create("bench", "bench", "{}");
}

void BM_NavIngestBatch1000(benchmark::State& state) {
  label(state);
  BenchDb file(state.range(0), "avk_bench_nav");
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
BENCHMARK(BM_NavIngestBatch1000)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_StoreTurn(benchmark::State& state) {
  label(state);
  BenchDb file(state.range(0), "avk_bench_turn");
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
BENCHMARK(BM_StoreTurn)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->UseRealTime();

avk::kinematics::TurnSequence bench_turn(unsigned seed, double u, double d) {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = u;
  spec.dheading_deg = d;
  spec.lead_in_m = 0.5 + u;
  spec.radius_m = 1.0 + 2.0 * u;
  spec.dt_s = 0.1;
  spec.position_noise_m = 0.1;
  spec.seed = seed;
  spec.vehicle_id = "bench";
  return avk::testing::make_arc_turn(spec);
}

// Figure 4-1's mission as the recorder writes it: 18 cells x 5 turns, each turn with its event,
// and 30 minutes of navigation at 10 Hz flushed once a second (10 rows a write).
void BM_StoreFigure41Mission(benchmark::State& state) {
  label(state);
  BenchDb file(state.range(0), "avk_bench_fig41");
  avk::store::Store s(file.path());
  std::vector<avk::kinematics::TurnSequence> turns;
  for (unsigned i = 0; i < 90; ++i)
    turns.push_back(bench_turn(i + 1, 0.5 + 0.5 * ((i % 18) / 6), 10.0 + 30.0 * (i % 6)));
  std::vector<avk::store::NavRow> second(10);
  for (auto _ : state) {
    const auto m = mission(s);
    for (int k = 0; k < 1800; ++k) {
      for (int j = 0; j < 10; ++j)
        second[static_cast<std::size_t>(j)] = {k + 0.1 * j, 1.0 * k, 0.5 * j, 90.0,
                                               1.0,         90.0,    1.0,     "turn"};
      s.navigation().append(m, second);
      if (k % 20 == 19) {
        const auto& t = turns[static_cast<std::size_t>(k / 20)];
        s.turns().add(m, t, avk::kinematics::TurnStatus::ok, "", {2.0, {}, {}});
        s.missions().append_event(m, k, "turn_done", "turn stored");
      }
    }
  }
  state.counters["nav_rows"] = 18000;
  state.counters["turns"] = 90;
}
BENCHMARK(BM_StoreFigure41Mission)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2)
    ->UseRealTime();

// Three stations (three connections, three threads) each storing 50 turns of its own mission at
// once into one database.
void BM_ThreeStationsWritingAtOnce(benchmark::State& state) {
  label(state);
  BenchDb file(state.range(0), "avk_bench_three");
  const auto turn = bench_turn(7, 1.0, 70.0);
  {
    avk::store::Store s(file.path());
    mission(s);
  }
  for (auto _ : state) {
    std::vector<std::thread> stations;
    for (int k = 0; k < 3; ++k)
      stations.emplace_back([&] {
        avk::store::Store s(file.path());
        const auto m = mission(s);
        for (int i = 0; i < 50; ++i)
          s.turns().add(m, turn, avk::kinematics::TurnStatus::ok, "", {2.0, {}, {}});
      });
    for (auto& t : stations)
      t.join();
  }
  state.SetItemsProcessed(state.iterations() * 150);
}
BENCHMARK(BM_ThreeStationsWritingAtOnce)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// 10,000 ok turns over the thesis' 18 cells (0.5/1.0/1.5 m/s x 10..160 deg, ~556 a cell), sampled
// at 10 Hz with 0.1 m position noise, from a vehicle whose lead-in and radius grow with speed.
// Storing them takes seconds, so the three benchmarks below share one database built on first use.
class StoredTurns {
 public:
  static StoredTurns& get(std::int64_t engine) {
    static StoredTurns lite(0), pg(1);
    return engine == 0 ? lite : pg;
  }
  std::string path() const { return file_.path(); }
  std::size_t samples() const { return samples_; }

 private:
  explicit StoredTurns(std::int64_t engine) : file_(engine, "avk_bench_ckt") {
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
  BenchDb file_;
  std::size_t samples_ = 0;
};

void BM_CktFrom10000StoredTurns(benchmark::State& state) {
  label(state);
  auto& data = StoredTurns::get(state.range(0));
  avk::store::Store s(data.path());
  for (auto _ : state) {
    const auto turns = s.turns().load_normalized({});
    benchmark::DoNotOptimize(avk::kinematics::Ckt::build(turns));
  }
  state.counters["samples"] = static_cast<double>(data.samples());
}
BENCHMARK(BM_CktFrom10000StoredTurns)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LoadNormalized10000Turns(benchmark::State& state) {
  label(state);
  auto& data = StoredTurns::get(state.range(0));
  avk::store::Store s(data.path());
  for (auto _ : state)
    benchmark::DoNotOptimize(s.turns().load_normalized({}));
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_LoadNormalized10000Turns)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_CktBuild10000Turns(benchmark::State& state) {
  label(state);
  auto& data = StoredTurns::get(state.range(0));
  const auto turns = avk::store::Store(data.path()).turns().load_normalized({});
  for (auto _ : state)
    benchmark::DoNotOptimize(avk::kinematics::Ckt::build(turns));
}
BENCHMARK(BM_CktBuild10000Turns)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
