#pragma once
// Identification data for the black-box yaw model (thesis §3.4.2): asynchronous navigation and
// guidance postings resampled to one fixed rate by linear interpolation between logged values.
// Headings are unwrapped before interpolating (350 -> 10 deg passes through 0, never 180), and a
// gap in any stream longer than the limit splits the data into segments, so that no regressor
// window spans a gap.

#include <cstddef>
#include <vector>

namespace avk::kinematics {

struct TimedValue {
  double t_s = 0.0;
  double value = 0.0;
};

// Each stream in time order (equal times allowed: the last posting wins).
struct NavStreams {
  std::vector<TimedValue> heading_deg;  // deg clockwise from north, any wrap
  std::vector<TimedValue> desired_heading_deg;
  std::vector<TimedValue> x_m;
  std::vector<TimedValue> y_m;
  std::vector<TimedValue> speed_mps;
  std::vector<TimedValue> desired_speed_mps;  // may be empty
};

struct ResampleOptions {
  double rate_hz = 4.0;  // thesis: 4 Hz, pMarinePID's AppTick
  // A longer silence in any navigation stream starts a new segment. Guidance streams only bound
  // the data in time (a helm may post only on change).
  double max_gap_s = 2.0;
  std::size_t min_samples = 8;  // shorter segments are dropped
};

// One stretch of synchronous samples, t_k = t0_s + k / rate_hz.
struct IdentSegment {
  double t0_s = 0.0;
  double dt_s = 0.25;
  std::vector<double> heading_deg;  // unwrapped: consecutive values differ by < 180
  // Unwrapped, and placed within 180 deg of the heading at the segment start, so that
  // desired - heading is the wrapped heading error wherever the two stay within 180 deg.
  std::vector<double> desired_heading_deg;
  std::vector<double> x_m;
  std::vector<double> y_m;
  std::vector<double> speed_mps;
  std::vector<double> desired_speed_mps;  // empty when the streams had none

  std::size_t size() const { return heading_deg.size(); }
  double t_at_s(std::size_t k) const { return t0_s + static_cast<double>(k) * dt_s; }
  // desired - heading, wrapped to (-180, 180]
  double error_deg(std::size_t k) const;
};

// Throws std::invalid_argument for a non-positive rate or gap, or a stream whose time decreases.
std::vector<IdentSegment> resample(const NavStreams& streams, const ResampleOptions& options = {});

// Linear interpolation of one stream at t (unwrapped first when `angle`): the building block,
// exposed for tests. Requires t within the stream's time range.
double interpolate_at(const std::vector<TimedValue>& stream, double t_s, bool angle);

// Cuts segments into pieces of at most max_length_s (a long continuous excitation log becomes
// several pieces, so a split by segment has material on both sides). Taken by value: a caller
// done with its segments moves them in, and each is released once cut.
std::vector<IdentSegment> split_long_segments(std::vector<IdentSegment> segments,
                                              double max_length_s);

}  // namespace avk::kinematics
