#include "mission/helm_loop.hpp"

#include <cmath>
#include <stdexcept>

namespace avk::mission {

void helm_tick(MissionRunner& runner, double now_s, double end_s, const std::atomic<bool>* stop,
               const std::function<void(double)>& before_tick, HelmLoopResult& result) {
  if (stop && stop->load()) {
    result.stopped = true;
    runner.interrupt(now_s, "stopped by a signal");
  } else if (now_s >= end_s) {
    result.horizon_reached = true;
    runner.interrupt(now_s, "time limit reached");
  } else {
    if (before_tick) before_tick(now_s);
    runner.tick(now_s);
  }
}

HelmLoopResult run_helm_loop(MissionRunner& runner, const vehicle::ScaledClock& clock,
                             double helm_hz, double max_duration_s, const std::atomic<bool>* stop,
                             const std::function<void(double)>& before_tick) {
  if (!(helm_hz > 0.0)) throw std::invalid_argument("helm rate must be positive");
  HelmLoopResult result;
  const double period = 1.0 / helm_hz;
  result.start_time_s = clock.now_s();
  double previous = result.start_time_s;
  double due = result.start_time_s;
  while (!runner.finished()) {
    clock.sleep_until(due);
    const double now = clock.now_s();
    if (now - previous > kStarvedAfterTicks * period) result.starved_s += now - previous - period;
    previous = now;
    helm_tick(runner, now, result.start_time_s + max_duration_s + result.starved_s, stop,
              before_tick, result);
    due += period;
    if (due < clock.now_s()) due = std::ceil(clock.now_s() / period) * period;
  }
  result.end_time_s = clock.now_s();
  return result;
}

}  // namespace avk::mission
