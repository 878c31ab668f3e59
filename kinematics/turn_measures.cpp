#include "kinematics/turn_measures.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/median.hpp"

namespace avk::kinematics {

namespace {

// Headings go through degree/radian conversions and sample-by-sample unwrapping, so an analytic
// 180-degree turn may end at 179.99999999999997; that still reaches 180.
constexpr double kHeadingEps_deg = 1e-6;

// Where a quantity sampled with the turn is read at a heading crossing: v[lo] + f * (v[hi] -
// v[lo]).
struct Crossing {
  std::size_t lo = 0;
  std::size_t hi = 0;
  double f = 0.0;
  template <class Get>
  double at(const std::vector<TurnSample>& s, Get get) const {
    return get(s[lo]) + f * (get(s[hi]) - get(s[lo]));
  }
};

std::optional<Crossing> first_crossing(const std::vector<TurnSample>& s, double target_deg) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i].heading_deg < target_deg - kHeadingEps_deg) continue;
    if (i == 0) return Crossing{0, 0, 0.0};
    const double h0 = s[i - 1].heading_deg;
    const double dh = s[i].heading_deg - h0;
    const double f = dh > 0.0 ? std::clamp((target_deg - h0) / dh, 0.0, 1.0) : 1.0;
    return Crossing{i - 1, i, f};
  }
  return std::nullopt;
}

struct SteadyTurn {
  double radius_m = 0.0;
  double yaw_rate_dps = 0.0;
};

std::optional<SteadyTurn> steady_turn(const std::vector<TurnSample>& s,
                                      const TurnMeasureOptions& o) {
  const std::size_t m = s.size() - 1;  // intervals
  std::vector<double> rate(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double dt = s[k + 1].t_s - s[k].t_s;
    // A non-increasing time stamp cannot give a rate; -inf keeps it out of every run.
    rate[k] = dt > 0.0 ? (s[k + 1].heading_deg - s[k].heading_deg) / dt
                       : -std::numeric_limits<double>::infinity();
  }
  std::vector<double> smooth = rate;
  for (std::size_t k = 1; k + 1 < m; ++k)
    smooth[k] = median3(rate[k - 1], rate[k], rate[k + 1]);

  // Longest window with max*(1-tol) <= min*(1+tol): shrinking a window can only restore the
  // condition, so a two-pointer sweep with monotone deques finds it in O(m).
  const double lo_k = 1.0 - o.steady_yaw_tolerance;
  const double hi_k = 1.0 + o.steady_yaw_tolerance;
  std::deque<std::size_t> maxq, minq;
  std::size_t left = 0;
  std::optional<std::pair<std::size_t, std::size_t>> best;  // [first, last] interval
  double best_duration_s = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    if (!(smooth[j] >= o.min_steady_yaw_rate_dps)) {
      maxq.clear();
      minq.clear();
      left = j + 1;
      continue;
    }
    while (!maxq.empty() && smooth[maxq.back()] <= smooth[j])
      maxq.pop_back();
    maxq.push_back(j);
    while (!minq.empty() && smooth[minq.back()] >= smooth[j])
      minq.pop_back();
    minq.push_back(j);
    while (smooth[maxq.front()] * lo_k > smooth[minq.front()] * hi_k) {
      ++left;
      while (maxq.front() < left)
        maxq.pop_front();
      while (minq.front() < left)
        minq.pop_front();
    }
    const auto intervals = static_cast<int>(j - left + 1);
    const double duration_s = s[j + 1].t_s - s[left].t_s;
    const double dheading_deg = s[j + 1].heading_deg - s[left].heading_deg;
    if (intervals >= o.min_steady_intervals && dheading_deg >= o.min_steady_dheading_deg &&
        duration_s > best_duration_s) {
      best = {left, j};
      best_duration_s = duration_s;
    }
  }
  if (!best) return std::nullopt;

  const auto [first, last] = *best;
  double speed_time_m = 0.0;  // integral of speed dt (trapezoid)
  for (std::size_t k = first; k <= last; ++k) {
    speed_time_m += 0.5 * (s[k].speed_mps + s[k + 1].speed_mps) * (s[k + 1].t_s - s[k].t_s);
  }
  const double speed_mps = speed_time_m / best_duration_s;
  const double yaw_rate_dps = (s[last + 1].heading_deg - s[first].heading_deg) / best_duration_s;
  if (!(speed_mps > 0.0)) return std::nullopt;
  return SteadyTurn{speed_mps / deg_to_rad(yaw_rate_dps), yaw_rate_dps};
}

}  // namespace

AdvanceTransfer advance_transfer(const Polyline& normalized) {
  if (normalized.empty()) {
    throw std::invalid_argument("advance_transfer: the turn has no points");
  }
  const Point& a = normalized.front();
  const Point& b = normalized.back();
  return {b.y_m - a.y_m, b.x_m - a.x_m};
}

AdvanceTransfer advance_transfer(const TurnSequence& turn) {
  if (turn.samples().empty()) {
    throw std::invalid_argument("advance_transfer: the turn has no samples");
  }
  if (turn.meta().normalized) return advance_transfer(turn.points());
  return advance_transfer(turn.normalized().points());
}

TurnMeasures measure_turn(const TurnSequence& turn, std::optional<double> vehicle_length_m) {
  return measure_turn(turn, TurnMeasureOptions{}, vehicle_length_m);
}

TurnMeasures measure_turn(const TurnSequence& turn, const TurnMeasureOptions& options,
                          std::optional<double> vehicle_length_m) {
  if (turn.samples().size() < 2) {
    throw std::invalid_argument("measure_turn: the turn has " +
                                std::to_string(turn.samples().size()) +
                                " sample(s); at least 2 are needed");
  }
  const TurnSequence norm = turn.normalized();
  const std::vector<TurnSample>& s = norm.samples();
  const TurnSample& first = s.front();

  TurnMeasures m;
  m.vehicle_length_m = vehicle_length_m;
  m.at_end = {s.back().y_m - first.y_m, s.back().x_m - first.x_m};

  const auto x_of = [](const TurnSample& p) { return p.x_m; };
  const auto y_of = [](const TurnSample& p) { return p.y_m; };
  const auto t_of = [](const TurnSample& p) { return p.t_s; };

  if (const auto c90 = first_crossing(s, 90.0)) {
    m.advance_90_m = c90->at(s, y_of) - first.y_m;
    m.transfer_90_m = c90->at(s, x_of) - first.x_m;
    m.time_to_90_s = c90->at(s, t_of) - first.t_s;
  }
  if (const auto c180 = first_crossing(s, 180.0)) {
    m.tactical_diameter_m = c180->at(s, x_of) - first.x_m;
    m.time_to_180_s = c180->at(s, t_of) - first.t_s;
  }
  if (const auto c10 = first_crossing(s, 10.0)) {
    double run_m = 0.0;
    for (std::size_t i = 1; i <= c10->lo; ++i)
      run_m += std::hypot(s[i].x_m - s[i - 1].x_m, s[i].y_m - s[i - 1].y_m);
    if (c10->hi != c10->lo) {
      run_m +=
          c10->f * std::hypot(s[c10->hi].x_m - s[c10->lo].x_m, s[c10->hi].y_m - s[c10->lo].y_m);
    }
    m.distance_to_first_10deg_m = run_m;
  }

  if (const auto steady = steady_turn(s, options)) {
    m.steady_turning_radius_m = steady->radius_m;
    m.steady_yaw_rate_dps = steady->yaw_rate_dps;
  }

  if (first.speed_mps > 0.0) {
    double min_speed_mps = first.speed_mps;
    for (const auto& p : s)
      min_speed_mps = std::min(min_speed_mps, p.speed_mps);
    m.speed_loss_mps = first.speed_mps - min_speed_mps;
    m.speed_loss_fraction = *m.speed_loss_mps / first.speed_mps;
  }

  double max_dheading_deg = s.front().heading_deg;
  for (const auto& p : s)
    max_dheading_deg = std::max(max_dheading_deg, p.heading_deg);
  m.max_dheading_deg = max_dheading_deg;
  const double goal_deg = std::abs(norm.meta().goal_dheading_deg);
  if (goal_deg > 0.0 && max_dheading_deg >= goal_deg - options.goal_reached_tolerance_deg) {
    m.overshoot_deg = std::max(0.0, max_dheading_deg - goal_deg);
  }
  return m;
}

std::optional<double> in_vehicle_lengths(std::optional<double> metres,
                                         std::optional<double> vehicle_length_m) {
  if (!metres || !vehicle_length_m || !(*vehicle_length_m > 0.0)) return std::nullopt;
  return *metres / *vehicle_length_m;
}

}  // namespace avk::kinematics
