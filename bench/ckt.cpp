// CKT speed targets: materialised lookup < 1 us, interpolated query < 20 us,
// materialising the 1 deg x 0.1 m/s table from 18 source cells < 50 ms.
#include <benchmark/benchmark.h>

#include <random>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "support/synthetic_turns.hpp"

using namespace avk::kinematics;

namespace {

// The thesis' Figure 4-1 grid: 3 speeds x 6 heading changes, 3 noisy turns a cell.
const Ckt& thesis_table() {
  static const Ckt table = Ckt::build(avk::testing::thesis_grid_turns(3, 0.1, 0.05));
  return table;
}

std::vector<std::pair<double, double>> random_queries(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5), d(-180.0, 180.0);
  std::vector<std::pair<double, double>> qs(1024);
  for (auto& q : qs)
    q = {u(rng), d(rng)};
  return qs;
}

void BM_MaterializedLookup(benchmark::State& state) {
  const MaterializedCkt m(thesis_table());
  const auto qs = random_queries(1);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& q = qs[i++ & 1023];
    benchmark::DoNotOptimize(m.lookup(q.first, q.second));
  }
}
BENCHMARK(BM_MaterializedLookup);

// What GET /predict answers: random speeds and heading changes, so nearly every query falls
// between the fine table's rows and columns.
void BM_MaterializedQueryOffGrid(benchmark::State& state) {
  const MaterializedCkt m(thesis_table());
  const auto qs = random_queries(3);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& q = qs[i++ & 1023];
    benchmark::DoNotOptimize(m.query(q.first, q.second));
  }
}
BENCHMARK(BM_MaterializedQueryOffGrid);

// A speed between two fine rows at a heading change between two columns: 0.75 m/s, which a
// nearest-row lookup answers from the 0.8 m/s row.
void BM_MaterializedQuery075(benchmark::State& state) {
  const MaterializedCkt m(thesis_table());
  for (auto _ : state)
    benchmark::DoNotOptimize(m.query(0.75, 55.5));
}
BENCHMARK(BM_MaterializedQuery075);

void BM_InterpolatedQuery(benchmark::State& state) {
  const Ckt& t = thesis_table();
  const auto qs = random_queries(2);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& q = qs[i++ & 1023];
    benchmark::DoNotOptimize(t.query(q.first, q.second));
  }
}
BENCHMARK(BM_InterpolatedQuery);

void BM_Materialize18Cells(benchmark::State& state) {
  const Ckt& t = thesis_table();
  for (auto _ : state) {
    MaterializedCkt m(t);
    benchmark::DoNotOptimize(m.speed_count());
  }
}
BENCHMARK(BM_Materialize18Cells)->Unit(benchmark::kMillisecond);

void BM_Build18CellsFrom54Turns(benchmark::State& state) {
  const Ckt& t = thesis_table();
  std::vector<TurnSequence> turns;
  for (const auto& c : t.cells())
    turns.insert(turns.end(), c.turns.begin(), c.turns.end());
  for (auto _ : state)
    benchmark::DoNotOptimize(Ckt::build(turns));
}
BENCHMARK(BM_Build18CellsFrom54Turns)->Unit(benchmark::kMillisecond);

void BM_CktFileRoundTrip(benchmark::State& state) {
  const std::string text = ckt_to_json_string(thesis_table());
  for (auto _ : state)
    benchmark::DoNotOptimize(ckt_to_json_string(parse_ckt_json(text)));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}
BENCHMARK(BM_CktFileRoundTrip)->Unit(benchmark::kMicrosecond);

}  // namespace
