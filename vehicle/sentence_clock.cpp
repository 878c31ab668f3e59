#include "vehicle/sentence_clock.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avk::vehicle {

namespace {

constexpr double kSecondsPerDay = 86400.0;

// x shifted by whole days into [-half a day, half a day).
double nearest_day(double x) {
  return x - kSecondsPerDay * std::floor(x / kSecondsPerDay + 0.5);
}

}  // namespace

SentenceClock::SentenceClock(SentenceClockConfig config) : config_(config) {
  if (!(config_.window_s > 0.0) || !(config_.max_ahead_s > 0.0) || !(config_.max_behind_s > 0.0) ||
      config_.reanchor_after < 1) {
    throw std::invalid_argument("sentence clock: window and limits must be positive");
  }
}

double SentenceClock::unwrapped_delay(double time_of_day_s, double read_s) const {
  const double delay = read_s - time_of_day_s;
  if (window_.empty()) return delay;
  const double offset = window_.front().delay_s;
  return offset + nearest_day(delay - offset);
}

void SentenceClock::push(const Delay& d) {
  while (!window_.empty() && window_.back().delay_s >= d.delay_s)
    window_.pop_back();
  window_.push_back(d);
}

bool SentenceClock::observe(double time_of_day_s, double read_s) {
  while (!window_.empty() && window_.front().read_s < read_s - config_.window_s)
    window_.pop_front();
  const Delay d{read_s, unwrapped_delay(time_of_day_s, read_s)};
  if (!window_.empty()) {
    // How much later than the offset predicts: negative when the sentence is ahead of the clock.
    const double late_s = d.delay_s - window_.front().delay_s;
    if (late_s < -config_.max_ahead_s || late_s > config_.max_behind_s) {
      if (++garbage_in_a_row_ < config_.reanchor_after) return false;
      window_.clear();
    }
  }
  garbage_in_a_row_ = 0;
  push(d);
  return true;
}

double SentenceClock::map(double time_of_day_s, double read_s) const {
  if (window_.empty()) return read_s;
  return std::min(read_s - unwrapped_delay(time_of_day_s, read_s) + window_.front().delay_s,
                  read_s);
}

void SentenceClock::reset() {
  window_.clear();
  garbage_in_a_row_ = 0;
}

}  // namespace avk::vehicle
