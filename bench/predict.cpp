// What a prediction that never saw a turn or a mission costs (Replay and Live's stored turns,
// predict?without_turn= / without_mission=): the first answer for a left-out set builds its table
// from the store, later ones look it up in the station's cache of held-out tables, where an
// ordinary prediction is a lookup in the vehicle's cached fine table. Measured through
// app::predict on a WAL database as the station runs it, for a vehicle of 180 and of 1,800 turns
// (18 cells x 10 / x 100, in 3 / 30 missions). Target: an ordinary prediction < 0.1 ms; a fair
// one < 100 ms at 180 turns the first time (a Replay seek or a page opened after a turn waits for
// it once), and a lookup after that.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "app/context.hpp"
#include "app/predict.hpp"
#include "app/store_access.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

using namespace avk;

namespace {

// A vehicle's turns stored in missions of 60 each: every mission covers all 18 cells, as a turn
// array flown with repeats does.
class Vehicle {
 public:
  static Vehicle& with(int per_cell) {
    static std::map<int, std::unique_ptr<Vehicle>> made;
    auto& v = made[per_cell];
    if (!v) v.reset(new Vehicle(per_cell));
    return *v;
  }
  app::Context& ctx() { return ctx_; }
  std::int64_t first_turn = 0;
  std::int64_t first_mission = 0;

 private:
  explicit Vehicle(int per_cell)
      : file_("avk_bench_predict_" + std::to_string(per_cell)), ctx_(file_.path()) {
    store::Store& s = app::store_of(ctx_);
    s.vehicles().upsert({"bench", "usim", 2.0, 1.0});
    constexpr double kSpeeds[] = {0.5, 1.0, 1.5};
    constexpr double kDheadings[] = {10.0, 40.0, 70.0, 100.0, 130.0, 160.0};
    std::int64_t mission = 0;
    for (int i = 0; i < 18 * per_cell; ++i) {
      if (i % 60 == 0) mission = s.missions().create("bench", "bench", "{}");
      if (first_mission == 0) first_mission = mission;
      const int cell = i % 18;
      testing::ArcTurnSpec spec;
      spec.speed_mps = kSpeeds[cell / 6];
      spec.dheading_deg = (i / 18) % 2 ? -kDheadings[cell % 6] : kDheadings[cell % 6];
      spec.lead_in_m = 0.5 + spec.speed_mps;
      spec.radius_m = 1.0 + 2.0 * spec.speed_mps;
      spec.dt_s = 0.1;
      spec.position_noise_m = 0.1;
      spec.seed = static_cast<unsigned>(i + 1);
      spec.vehicle_id = "bench";
      const auto id = s.turns().add(mission, testing::make_arc_turn(spec),
                                    kinematics::TurnStatus::ok, "", {2.0, {}, {}});
      if (first_turn == 0) first_turn = id;
    }
  }
  testing::TempDb file_;
  app::Context ctx_;
};

app::PredictQuery query() {
  app::PredictQuery q;
  q.vehicle_id = "bench";
  q.speed_mps = 1.0;
  q.dheading_deg = -70.0;
  q.pose = kinematics::Pose{10.0, -5.0, 30.0};
  return q;
}

void run(benchmark::State& state, const app::PredictQuery& q, app::Context& ctx) {
  for (auto _ : state) {
    auto p = app::predict(ctx, q);
    if (!p) state.SkipWithError(p.error().message.c_str());
    benchmark::DoNotOptimize(p);
  }
}

void BM_PredictCached(benchmark::State& state) {
  auto& v = Vehicle::with(static_cast<int>(state.range(0)));
  run(state, query(), v.ctx());
}
BENCHMARK(BM_PredictCached)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

// Arg 1: 0 without the vehicle's first turn, 1 without its first mission. The same set every
// time: the held-out table is built once, then looked up.
void BM_PredictHeldOut(benchmark::State& state) {
  auto& v = Vehicle::with(static_cast<int>(state.range(0)));
  auto q = query();
  if (state.range(1) == 0)
    q.without_turn_id = v.first_turn;
  else
    q.without_mission_id = v.first_mission;
  run(state, q, v.ctx());
}
BENCHMARK(BM_PredictHeldOut)
    ->ArgsProduct({{10, 100}, {0, 1}})
    ->ArgNames({"per_cell", "without_mission"})
    ->Unit(benchmark::kMillisecond);

// Another turn left out at every call: each answer builds its table (what the first request for
// a set costs).
void BM_PredictHeldOutFirst(benchmark::State& state) {
  const int per_cell = static_cast<int>(state.range(0));
  auto& v = Vehicle::with(per_cell);
  auto q = query();
  std::int64_t i = 0;
  for (auto _ : state) {
    q.without_turn_id = v.first_turn + i++ % (18 * per_cell);
    auto p = app::predict(v.ctx(), q);
    if (!p) state.SkipWithError(p.error().message.c_str());
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_PredictHeldOutFirst)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
