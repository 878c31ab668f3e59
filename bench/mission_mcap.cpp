// Exporting the Figure 4-1 mission (flown once on the simulated usim) as an MCAP recording: every
// navigation sample on four channels, each turn with its predictions and its stored record, every
// event; with zstd chunks and without. Measures the time and the file size.

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "app/context.hpp"
#include "app/mission_mcap.hpp"
#include "app/store_access.hpp"
#include "support/example_file.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

// Flown once for all the benchmarks: the mission is the input, not what is measured.
struct Figure41 {
  Figure41() : ctx(db.path()) {
    mission = avk::testing::run_recorded_mission(avk::app::store_of(ctx), "usim",
                                                 avk::testing::example_text("thesis-fig4-1.json"));
    nav = avk::app::store_of(ctx).navigation().for_mission(mission).size();
    // The vehicle's table is built once, as a running station holds it in its cache.
    (void)avk::app::export_mission_mcap(ctx, mission);
  }
  avk::testing::TempDb db{"avk_bench_mcap"};
  avk::app::Context ctx;
  std::int64_t mission = 0;
  std::size_t nav = 0;
};

Figure41& figure41() {
  static Figure41 f;
  return f;
}

void export_mcap(benchmark::State& state, avk::app::mcap::Compression c) {
  Figure41& f = figure41();
  avk::app::McapExportOptions o;
  o.compression = c;
  std::size_t bytes = 0;
  std::uint64_t messages = 0;
  for (auto _ : state) {
    auto r = avk::app::export_mission_mcap(f.ctx, f.mission, o);
    if (!r) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    bytes = r->bytes.size();
    messages = r->messages.total();
    benchmark::DoNotOptimize(r->bytes.data());
  }
  state.counters["file_bytes"] = static_cast<double>(bytes);
  state.counters["messages"] = static_cast<double>(messages);
  state.counters["nav_samples"] = static_cast<double>(f.nav);
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes) * state.iterations());
}

void BM_ExportFigure41Zstd(benchmark::State& state) {
  export_mcap(state, avk::app::mcap::Compression::zstd);
}
BENCHMARK(BM_ExportFigure41Zstd)->Unit(benchmark::kMillisecond);

void BM_ExportFigure41Uncompressed(benchmark::State& state) {
  export_mcap(state, avk::app::mcap::Compression::none);
}
BENCHMARK(BM_ExportFigure41Uncompressed)->Unit(benchmark::kMillisecond);

}  // namespace
