#pragma once
// The mission-clock time of a frontseat sentence, from the time of day it carries (seconds since
// midnight UTC on a boat; the emulator's own clock at its realtime factor). One read from a link
// can hold many sentences, so the time a read returned says little about when each was sent;
// the sentence's own time does.
//
// The rule: mission time = sentence time + offset, where the offset is the smallest transport
// delay (read time minus sentence time) seen over the last window_s of reads. The smallest delay
// is the one least disturbed by queueing, and a sliding window lets it follow a frontseat clock
// that drifts against ours and forgets a delay that was a fluke. A mapped time is never later
// than the read that brought the sentence. Midnight wraps: times are unwrapped to the day that
// puts them nearest the clock. A time more than max_ahead_s ahead of the clock, or more than
// max_behind_s behind it, is garbage: it is not used and does not move the offset, so one bad
// field cannot shift every later stamp. reanchor_after garbage times in a row are not garbage
// but a frontseat clock that jumped (set by GPS, or a restart): the clock starts again from them.
// No I/O, not thread-safe.

#include <deque>

namespace avk::vehicle {

struct SentenceClockConfig {
  double window_s = 20.0;
  double max_ahead_s = 2.0;
  double max_behind_s = 60.0;
  int reanchor_after = 10;
};

class SentenceClock {
 public:
  explicit SentenceClock(SentenceClockConfig config = {});

  // Takes in a sentence time of day read at read_s on the mission clock. False when it is
  // garbage: it then has no mission time, and the caller falls back to its own estimate.
  bool observe(double time_of_day_s, double read_s);

  // The mission time of a sentence time of day that observe() accepted, read at read_s: never
  // after read_s. Observe every sentence of a read before mapping any, so that all of them are
  // mapped with the offset the whole read gave. Without an accepted time yet, read_s.
  double map(double time_of_day_s, double read_s) const;

  // Forgets everything: a new link may reach a frontseat with another clock.
  void reset();

 private:
  struct Delay {
    double read_s;
    double delay_s;  // read_s - the sentence time, unwrapped to the anchor's day
  };
  double unwrapped_delay(double time_of_day_s, double read_s) const;
  void push(const Delay& d);

  SentenceClockConfig config_;
  // The window's candidates for its minimum, oldest first, delays increasing: the front is the
  // offset. A delay is dropped when a later one is smaller, since it can never be the minimum.
  std::deque<Delay> window_;
  int garbage_in_a_row_ = 0;
};

}  // namespace avk::vehicle
