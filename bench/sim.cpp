// Simulated seconds per wall second for the full stack (plant + sensor + pMarinePID + a
// constant-heading helm) at default rates: target >= 10,000x real time on one core.
#include <benchmark/benchmark.h>

#include "sim/scheduler.hpp"
#include "sim/sim_vehicle.hpp"

using namespace avk::sim;

namespace {

void run_stack(benchmark::State& state, const std::string& kind) {
  const double sim_s = 3600.0;
  for (auto _ : state) {
    Scheduler scheduler;
    SimVehicle v(sim_vehicle_defaults(kind), scheduler);
    double heading = 0.0;
    // A helm that changes course every 60 s so the controller and plant work the whole hour.
    scheduler.add("helm", 4.0, [&](double now) {
      heading = std::fmod(std::floor(now / 60.0) * 70.0, 360.0);
      benchmark::DoNotOptimize(v.take_nav());
      v.command({now, heading, 1.0});
    });
    scheduler.run_until(sim_s);
    benchmark::DoNotOptimize(v.truth());
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(
      sim_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_FullStackUsim(benchmark::State& state) {
  run_stack(state, "usim");
}
void BM_FullStackCatamaranM200(benchmark::State& state) {
  run_stack(state, "catamaran:m200");
}
void BM_FullStackCatamaranOtter(benchmark::State& state) {
  run_stack(state, "catamaran:otter");
}
BENCHMARK(BM_FullStackUsim)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullStackCatamaranM200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullStackCatamaranOtter)->Unit(benchmark::kMillisecond);

}  // namespace
