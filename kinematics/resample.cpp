#include "kinematics/resample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

double IdentSegment::error_deg(std::size_t k) const {
  return angle180_deg(desired_heading_deg[k] - heading_deg[k]);
}

namespace {

void check_stream(const std::vector<TimedValue>& s, const char* name) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i].t_s) || !std::isfinite(s[i].value))
      throw std::invalid_argument(std::string(name) + " sample " + std::to_string(i) +
                                  " is not finite");
    if (i && s[i].t_s < s[i - 1].t_s)
      throw std::invalid_argument(std::string(name) + " time decreases at sample " +
                                  std::to_string(i));
  }
}

// A stream with angles unwrapped, so interpolation never crosses a wrap the long way round.
std::vector<TimedValue> unwrapped(const std::vector<TimedValue>& s) {
  std::vector<TimedValue> out = s;
  for (std::size_t i = 1; i < out.size(); ++i)
    out[i].value = out[i - 1].value + angle180_deg(s[i].value - out[i - 1].value);
  return out;
}

// Walks a stream forward as the sample times grow: O(n + m) over a whole resampling.
class Cursor {
 public:
  explicit Cursor(const std::vector<TimedValue>& s) : s_(s) {}
  double at(double t) {
    while (i_ + 1 < s_.size() && s_[i_ + 1].t_s <= t)
      ++i_;
    if (i_ + 1 >= s_.size() || s_[i_].t_s >= t) return s_[i_].value;
    const TimedValue& a = s_[i_];
    const TimedValue& b = s_[i_ + 1];
    return a.value + (b.value - a.value) * (t - a.t_s) / (b.t_s - a.t_s);
  }

 private:
  const std::vector<TimedValue>& s_;
  std::size_t i_ = 0;
};

// Intervals [start, end] where every required stream has samples no further apart than max_gap.
std::vector<std::pair<double, double>> covered_intervals(
    const std::vector<const std::vector<TimedValue>*>& streams, double max_gap) {
  std::vector<std::pair<double, double>> cover;
  for (std::size_t k = 0; k < streams.size(); ++k) {
    const auto& s = *streams[k];
    std::vector<std::pair<double, double>> mine;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (mine.empty() || s[i].t_s - s[i - 1].t_s > max_gap) {
        mine.push_back({s[i].t_s, s[i].t_s});
      } else {
        mine.back().second = s[i].t_s;
      }
    }
    if (k == 0) {
      cover = std::move(mine);
      continue;
    }
    std::vector<std::pair<double, double>> both;
    std::size_t a = 0, b = 0;
    while (a < cover.size() && b < mine.size()) {
      const double lo = std::max(cover[a].first, mine[b].first);
      const double hi = std::min(cover[a].second, mine[b].second);
      if (lo <= hi) both.push_back({lo, hi});
      if (cover[a].second < mine[b].second) {
        ++a;
      } else {
        ++b;
      }
    }
    cover = std::move(both);
  }
  return cover;
}

}  // namespace

double interpolate_at(const std::vector<TimedValue>& stream, double t_s, bool angle) {
  if (stream.empty()) throw std::invalid_argument("interpolate_at: empty stream");
  if (t_s < stream.front().t_s || t_s > stream.back().t_s)
    throw std::invalid_argument("interpolate_at: time outside the stream");
  const std::vector<TimedValue> s = angle ? unwrapped(stream) : stream;
  Cursor c(s);
  return c.at(t_s);
}

std::vector<IdentSegment> resample(const NavStreams& in, const ResampleOptions& options) {
  if (!(options.rate_hz > 0.0) || !std::isfinite(options.rate_hz))
    throw std::invalid_argument("resample: rate_hz must be positive");
  if (!(options.max_gap_s > 0.0))
    throw std::invalid_argument("resample: max_gap_s must be positive");
  check_stream(in.heading_deg, "heading");
  check_stream(in.desired_heading_deg, "desired heading");
  check_stream(in.x_m, "x");
  check_stream(in.y_m, "y");
  check_stream(in.speed_mps, "speed");
  check_stream(in.desired_speed_mps, "desired speed");
  std::vector<const std::vector<TimedValue>*> required = {&in.heading_deg, &in.desired_heading_deg,
                                                          &in.x_m, &in.y_m, &in.speed_mps};
  const bool has_desired_speed = !in.desired_speed_mps.empty();
  if (has_desired_speed) required.push_back(&in.desired_speed_mps);
  for (const auto* s : required)
    if (s->empty()) return {};

  const std::vector<TimedValue> heading = unwrapped(in.heading_deg);
  const std::vector<TimedValue> desired = unwrapped(in.desired_heading_deg);
  const double dt = 1.0 / options.rate_hz;
  std::vector<IdentSegment> out;
  // Guidance is posted when the helm runs (or only on change): it bounds the data in time but
  // its silences are not navigation gaps.
  std::vector<const std::vector<TimedValue>*> navigation(required.begin(), required.begin() + 1);
  navigation.push_back(&in.x_m);
  navigation.push_back(&in.y_m);
  navigation.push_back(&in.speed_mps);
  double guidance_begin = in.desired_heading_deg.front().t_s;
  double guidance_end = in.desired_heading_deg.back().t_s;
  if (has_desired_speed) {
    guidance_begin = std::max(guidance_begin, in.desired_speed_mps.front().t_s);
    guidance_end = std::min(guidance_end, in.desired_speed_mps.back().t_s);
  }
  for (auto [t_begin, t_end] : covered_intervals(navigation, options.max_gap_s)) {
    t_begin = std::max(t_begin, guidance_begin);
    t_end = std::min(t_end, guidance_end);
    // Grid times are whole multiples of dt, so segments of different logs line up.
    const double first = std::ceil(t_begin / dt - 1e-9) * dt;
    if (first > t_end) continue;
    const auto n = static_cast<std::size_t>(std::floor((t_end - first) / dt + 1e-9)) + 1;
    if (n < options.min_samples) continue;
    IdentSegment seg;
    seg.t0_s = first;
    seg.dt_s = dt;
    Cursor h(heading), d(desired), x(in.x_m), y(in.y_m), u(in.speed_mps), ud(in.desired_speed_mps);
    for (std::size_t k = 0; k < n; ++k) {
      const double t = first + static_cast<double>(k) * dt;
      seg.heading_deg.push_back(h.at(t));
      seg.desired_heading_deg.push_back(d.at(t));
      seg.x_m.push_back(x.at(t));
      seg.y_m.push_back(y.at(t));
      seg.speed_mps.push_back(u.at(t));
      if (has_desired_speed) seg.desired_speed_mps.push_back(ud.at(t));
    }
    // The desired stream was unwrapped on its own; move it by whole turns next to the heading.
    const double shift =
        360.0 * std::round((seg.heading_deg.front() - seg.desired_heading_deg.front()) / 360.0);
    for (double& v : seg.desired_heading_deg)
      v += shift;
    out.push_back(std::move(seg));
  }
  return out;
}

std::vector<IdentSegment> split_long_segments(std::vector<IdentSegment> segments,
                                              double max_length_s) {
  std::vector<IdentSegment> out;
  for (IdentSegment& s : segments) {
    const auto piece =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(max_length_s / s.dt_s)));
    for (std::size_t start = 0; start < s.size(); start += piece) {
      const std::size_t end = std::min(s.size(), start + piece);
      IdentSegment p;
      p.t0_s = s.t_at_s(start);
      p.dt_s = s.dt_s;
      const auto cut = [&](const std::vector<double>& v) {
        return v.empty() ? v : std::vector<double>(v.begin() + start, v.begin() + end);
      };
      p.heading_deg = cut(s.heading_deg);
      p.desired_heading_deg = cut(s.desired_heading_deg);
      p.x_m = cut(s.x_m);
      p.y_m = cut(s.y_m);
      p.speed_mps = cut(s.speed_mps);
      p.desired_speed_mps = cut(s.desired_speed_mps);
      out.push_back(std::move(p));
    }
    // Each segment is let go once cut, so a long record is held about once, not twice.
    s = IdentSegment{};
  }
  return out;
}

}  // namespace avk::kinematics
