#pragma once
// A clock and multi-rate scheduler in the manner of MOOS AppTicks: each component ticks at its own
// rate and phase and sees the others only through values they published. The same loop runs
// faster than real time (a pacer that never waits) or in real time (a pacer that sleeps until
// the wall clock catches up), so a simulation and a real-time run share one code path.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <random>
#include <string>
#include <vector>

namespace avk::sim {

// Decides how long a tick due at sim_time_s waits before it runs.
class Pacer {
 public:
  virtual ~Pacer() = default;
  virtual void wait_until(double sim_time_s) = 0;
};

// Faster than real time: never waits.
class FastPacer final : public Pacer {
 public:
  void wait_until(double) override {}
};

// Real time x factor (2 = twice as fast as the wall clock), on an Asio steady timer.
class RealtimePacer final : public Pacer {
 public:
  explicit RealtimePacer(double factor = 1.0);
  ~RealtimePacer() override;
  void wait_until(double sim_time_s) override;
  double factor() const { return factor_; }

 private:
  struct Impl;  // keeps Asio out of this header
  std::unique_ptr<Impl> impl_;
  double factor_;
};

struct SchedulerOptions {
  std::uint64_t seed = 1;
  // Each tick runs up to this fraction of its period late (uniform, seeded): the asynchronous
  // timing of MOOS publish/subscribe that made the thesis' simulated turns vary (Fig. 5-1, 5-2).
  double jitter_fraction = 0.0;
  // Start every component at a random phase within its period (seeded) instead of its own phase.
  bool random_phases = false;
  // The clock's first reading. A resumed mission continues its clock so that stored times
  // never repeat.
  double start_time_s = 0.0;
};

class Scheduler {
 public:
  using Tick = std::function<void(double now_s)>;

  explicit Scheduler(SchedulerOptions options = {});

  // Components due at the same instant run in the order they were added. Returns an id.
  std::size_t add(std::string name, double rate_hz, Tick tick, double phase_s = 0.0);

  double now_s() const { return now_s_; }
  std::size_t component_count() const { return components_.size(); }
  const std::string& name(std::size_t id) const { return components_.at(id).name; }
  double rate_hz(std::size_t id) const { return components_.at(id).rate_hz; }
  std::uint64_t ticks_run() const { return ticks_run_; }

  // Runs every tick due at or before t_end_s (or until request_stop()), then sets the clock to
  // t_end_s. Returns false when stopped early.
  bool run_until(double t_end_s, Pacer& pacer);
  bool run_until(double t_end_s);

  // Called from inside a tick: the current run_until returns after that tick.
  void request_stop() { stop_requested_ = true; }

 private:
  struct Component {
    std::string name;
    double rate_hz;
    double phase_s;
    Tick tick;
    std::uint64_t next_k = 0;
  };
  struct Due {
    double t_s;
    std::size_t id;
    bool operator>(const Due& o) const { return t_s != o.t_s ? t_s > o.t_s : id > o.id; }
  };
  double due_time(std::size_t id, std::uint64_t k);

  SchedulerOptions options_;
  std::mt19937_64 rng_;
  std::vector<Component> components_;
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> queue_;
  double now_s_ = 0.0;
  std::uint64_t ticks_run_ = 0;
  bool stop_requested_ = false;
};

}  // namespace avk::sim
