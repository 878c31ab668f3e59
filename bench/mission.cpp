// The whole Figure 4-1 collection mission (18 turns) against the simulator, recorded into a
// SQLite file as `avk mission run` does: the target is under 2 s of wall time per mission.

#include <benchmark/benchmark.h>

#include "support/temp_db.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include "app/mission_recorder.hpp"
#include "mission/mission_config.hpp"
#include "mission/mission_runner.hpp"
#include "mission/turn_plan.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_mission.hpp"
#include "store/store.hpp"

namespace {

std::string example(const std::string& name) {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/examples/" + name);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void run_mission(benchmark::State& state, const std::string& kind, const std::string& sim_config) {
  const avk::sim::SimSetup setup = sim_config.empty()
                                       ? avk::sim::default_sim_setup(kind)
                                       : avk::sim::parse_sim_config(example(sim_config), kind);
  const std::string text = example("thesis-fig4-1.json");
  const auto config = avk::mission::parse_mission_config(text, setup.vehicle_max_speed_mps());
  double simulated_s = 0.0;
  std::int64_t turns = 0;
  for (auto _ : state) {
    avk::testing::TempDb file("avk_bench_mission");
    avk::store::Store db(file.path());
    db.vehicles().upsert({"bench", kind, setup.vehicle_max_speed_mps(), std::nullopt});
    const auto id = db.missions().create("bench", config.name, text);
    avk::sim::SimMissionOptions so;
    so.setup = setup;
    so.start = {config.region.return_point.x_m, config.region.return_point.y_m, 0.0};
    avk::sim::SimMission sim(so);
    avk::app::MissionRecorder recorder(db, id);
    avk::mission::MissionRunner runner(config, sim.vehicle(), avk::mission::plan_turns(config),
                                       {"bench", std::to_string(id)});
    runner.add_observer(recorder);
    avk::sim::FastPacer pacer;
    const auto r = sim.run(runner, pacer);
    recorder.flush();
    simulated_s = r.end_time_s - r.start_time_s;
    if (runner.state() != avk::mission::MissionState::done) state.SkipWithError("mission not done");
    for (const auto& c : runner.cells())
      turns += c.ok;
  }
  state.counters["simulated_s"] = simulated_s;
  state.counters["turns_ok"] =
      benchmark::Counter(static_cast<double>(turns), benchmark::Counter::kAvgIterations);
}

void BM_Figure41Usim(benchmark::State& state) {
  run_mission(state, "usim", "");
}
BENCHMARK(BM_Figure41Usim)->Unit(benchmark::kMillisecond);

void BM_Figure41CatamaranM200(benchmark::State& state) {
  run_mission(state, "catamaran:m200", "");
}
BENCHMARK(BM_Figure41CatamaranM200)->Unit(benchmark::kMillisecond);

void BM_Figure41CatamaranChoppy(benchmark::State& state) {
  run_mission(state, "catamaran:m200", "sim-choppy.json");
}
BENCHMARK(BM_Figure41CatamaranChoppy)->Unit(benchmark::kMillisecond);

}  // namespace
