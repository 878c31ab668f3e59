// Maneuver evaluation target: 73 candidate heading changes x 10 contacts with the AVK
// prediction and its corridor in under 1 ms (target 0.2 ms). Measured twice: the pure
// computation over a materialised table, and the use case guidance calls (app::evaluate_maneuvers:
// the vehicle's cached table from its stored turns, validation, the same computation).
#include <benchmark/benchmark.h>

#include <random>

#include "app/context.hpp"
#include "app/maneuvers.hpp"
#include "app/store_access.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/maneuver.hpp"
#include "support/stored_turns.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

using namespace avk;
namespace kin = avk::kinematics;

namespace {

std::vector<kin::Contact> ten_contacts() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-80.0, 80.0), course(0.0, 360.0), speed(0.5, 1.5);
  std::vector<kin::Contact> out;
  for (int k = 0; k < 10; ++k)
    out.push_back({pos(rng), pos(rng), course(rng), speed(rng)});
  return out;
}

// Own speed on a fine-table row (1.0 m/s) and between rows (1.03 m/s, every query blended).
void BM_EvaluateManeuvers73x10(benchmark::State& state) {
  static const kin::Ckt table = kin::Ckt::build(avk::testing::thesis_grid_turns(3, 0.1, 0.05));
  static const kin::MaterializedCkt fine(table);
  const double speed = state.range(0) == 0 ? 1.0 : 1.03;
  kin::ManeuverProblem p;
  p.own = {0.0, 0.0, 30.0};
  p.contacts = ten_contacts();
  p.standoff_m = 10.0;
  p.horizon_s = 120.0;
  const auto candidates = kin::candidate_dheadings_deg(5.0);
  for (auto _ : state) {
    std::vector<kin::CandidateEvaluation> all;
    all.reserve(candidates.size());
    for (const double d : candidates) {
      const kin::TurnPrediction t = fine.query(speed, d);
      std::vector<double> w;
      if (t.corridor) w = kin::corridor_half_widths_m(t.trajectory, *t.corridor, 0.9);
      all.push_back(kin::evaluate_candidate(
          p, kin::timed_maneuver(d, speed, t.trajectory, t.timing, std::move(w))));
    }
    benchmark::DoNotOptimize(kin::choose_maneuver(all));
  }
  state.SetLabel(state.range(0) == 0 ? "on a fine row" : "between fine rows");
}
BENCHMARK(BM_EvaluateManeuvers73x10)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_AppEvaluateManeuvers73x10(benchmark::State& state) {
  avk::testing::TempDb db("avk_bench_maneuver");
  app::Context ctx(db.path());
  avk::testing::store_arc_turns(app::store_of(ctx), "bench", 1.0, 3);
  app::ManeuverQuery q;
  q.vehicle_id = "bench";
  q.own = {0.0, 0.0, 30.0};
  q.speed_mps = state.range(0) == 0 ? 1.0 : 1.03;
  q.contacts = ten_contacts();
  q.method =
      state.range(1) == 0 ? app::PredictionMethod::avk : app::PredictionMethod::instantaneous;
  if (!app::evaluate_maneuvers(ctx, q)) state.SkipWithError("no evaluation");  // warms the cache
  for (auto _ : state) {
    auto e = app::evaluate_maneuvers(ctx, q);
    benchmark::DoNotOptimize(e);
  }
  state.SetLabel(std::string(state.range(1) == 0 ? "avk" : "instantaneous") +
                 (state.range(0) == 0 ? ", on a fine row" : ", between fine rows"));
}
BENCHMARK(BM_AppEvaluateManeuvers73x10)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
