#pragma once
// The clock of a run against a vehicle on the network: seconds on the mission clock, advancing at
// factor x the wall clock from start_s. A factor above 1 is for a frontseat emulator that runs its
// plant faster than real time by the same factor; against a real boat it is 1. Thread-safe (the
// state is fixed at construction).

#include <chrono>
#include <stdexcept>
#include <thread>

namespace avk::vehicle {

class ScaledClock {
 public:
  using steady = std::chrono::steady_clock;

  explicit ScaledClock(double factor = 1.0, double start_s = 0.0)
      : factor_(factor), start_s_(start_s), wall_start_(steady::now()) {
    if (!(factor > 0.0 && factor <= 10000.0))
      throw std::invalid_argument("clock factor must be in (0, 10000]");
  }

  double now_s() const {
    return start_s_ + factor_ * std::chrono::duration<double>(steady::now() - wall_start_).count();
  }
  double factor() const { return factor_; }

  // The wall-clock instant at which now_s() reaches t_s.
  steady::time_point wall_time(double t_s) const {
    return wall_start_ + std::chrono::duration_cast<steady::duration>(
                             std::chrono::duration<double>((t_s - start_s_) / factor_));
  }
  // Clock seconds to wall-clock duration (a timeout given in mission seconds).
  steady::duration wall_duration(double clock_s) const {
    return std::chrono::duration_cast<steady::duration>(
        std::chrono::duration<double>(clock_s / factor_));
  }
  void sleep_until(double t_s) const { std::this_thread::sleep_until(wall_time(t_s)); }

 private:
  double factor_;
  double start_s_;
  steady::time_point wall_start_;
};

}  // namespace avk::vehicle
