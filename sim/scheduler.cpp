#include "sim/scheduler.hpp"

#include <cmath>
#include <stdexcept>

namespace avk::sim {

Scheduler::Scheduler(SchedulerOptions options)
    : options_(options), rng_(options.seed), now_s_(options.start_time_s) {
  if (!std::isfinite(options.start_time_s) || options.start_time_s < 0.0) {
    throw std::invalid_argument("scheduler start_time_s must be a finite time >= 0 s");
  }
  if (!(options.jitter_fraction >= 0.0 && options.jitter_fraction < 1.0)) {
    throw std::invalid_argument("scheduler jitter_fraction must be in [0, 1)");
  }
}

std::size_t Scheduler::add(std::string name, double rate_hz, Tick tick, double phase_s) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument("tick rate of '" + name + "' must be a positive number of Hz");
  }
  if (!(phase_s >= 0.0) || !std::isfinite(phase_s)) {
    throw std::invalid_argument("phase of '" + name + "' must be >= 0 s");
  }
  if (options_.random_phases) {
    phase_s = std::uniform_real_distribution<double>(0.0, 1.0 / rate_hz)(rng_);
  }
  const std::size_t id = components_.size();
  components_.push_back({std::move(name), rate_hz, now_s_ + phase_s, std::move(tick), 0});
  queue_.push({due_time(id, 0), id});
  return id;
}

double Scheduler::due_time(std::size_t id, std::uint64_t k) {
  const Component& c = components_[id];
  // Nominal times are computed, not accumulated, so a long run does not drift.
  double t = c.phase_s + static_cast<double>(k) / c.rate_hz;
  if (options_.jitter_fraction > 0.0) {
    t += std::uniform_real_distribution<double>(0.0, options_.jitter_fraction / c.rate_hz)(rng_);
  }
  return t;
}

bool Scheduler::run_until(double t_end_s, Pacer& pacer) {
  stop_requested_ = false;
  while (!queue_.empty() && queue_.top().t_s <= t_end_s) {
    const Due due = queue_.top();
    queue_.pop();
    pacer.wait_until(due.t_s);
    now_s_ = due.t_s;
    Component& c = components_[due.id];
    c.tick(now_s_);
    ++ticks_run_;
    ++c.next_k;
    queue_.push({due_time(due.id, c.next_k), due.id});
    if (stop_requested_) return false;
  }
  pacer.wait_until(t_end_s);
  now_s_ = std::max(now_s_, t_end_s);
  return true;
}

bool Scheduler::run_until(double t_end_s) {
  FastPacer fast;
  return run_until(t_end_s, fast);
}

}  // namespace avk::sim
