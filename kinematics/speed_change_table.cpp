#include "kinematics/speed_change_table.hpp"

#include <algorithm>
#include <cmath>

namespace avk::kinematics {

SpeedChangeTable SpeedChangeTable::build(const std::vector<TurnSequence>& turns,
                                         const CktOptions& options) {
  SpeedChangeTable out;
  out.speed_match_mps_ = options.speed_match_mps;
  std::vector<std::vector<TurnSequence>> members;
  for (const auto& t : turns) {
    const TurnMeta& m = t.meta();
    if (m.status != TurnStatus::ok || !m.speed_after_mps) continue;
    std::size_t k = 0;
    while (k < out.pairs_.size() &&
           !(within_match(out.pairs_[k].from_mps, m.commanded_speed_mps, options.speed_match_mps) &&
             within_match(out.pairs_[k].to_mps, *m.speed_after_mps, options.speed_match_mps)))
      ++k;
    if (k == out.pairs_.size()) {
      out.pairs_.push_back({m.commanded_speed_mps, *m.speed_after_mps, Ckt{}});
      members.emplace_back();
    }
    // Ckt::build keeps speed-change turns out of its constant-speed cells; within one pair the
    // speed after is the same for all, so the copy is built as a constant-speed row at u0.
    TurnSequence copy = t;
    copy.meta().speed_after_mps.reset();
    members[k].push_back(std::move(copy));
  }
  for (std::size_t k = 0; k < out.pairs_.size(); ++k) {
    CktGrid grid;
    grid.speeds_mps = {out.pairs_[k].from_mps};
    std::vector<double> d;
    for (const auto& t : members[k])
      d.push_back(std::round(std::abs(t.meta().goal_dheading_deg) * 10.0) / 10.0);
    std::sort(d.begin(), d.end());
    d.erase(std::unique(d.begin(), d.end(),
                        [&](double a, double b) { return b - a < options.dheading_match_deg; }),
            d.end());
    grid.dheadings_deg = d;
    out.pairs_[k].table = Ckt::build(members[k], options, grid);
  }
  std::sort(out.pairs_.begin(), out.pairs_.end(), [](const auto& a, const auto& b) {
    return a.from_mps != b.from_mps ? a.from_mps < b.from_mps : a.to_mps < b.to_mps;
  });
  return out;
}

const SpeedChangeCells* SpeedChangeTable::find(double from_mps, double to_mps) const {
  const SpeedChangeCells* best = nullptr;
  double best_d = 0.0;
  for (const auto& p : pairs_) {
    const double a = std::abs(p.from_mps - from_mps), b = std::abs(p.to_mps - to_mps);
    if (a > speed_match_mps_ || b > speed_match_mps_) continue;
    if (!best || a + b < best_d) {
      best = &p;
      best_d = a + b;
    }
  }
  return best;
}

std::optional<TurnPrediction> SpeedChangeTable::query(double from_mps, double to_mps,
                                                      double dheading_deg) const {
  const SpeedChangeCells* p = find(from_mps, to_mps);
  if (!p || !p->table.speed_range_mps()) return std::nullopt;
  TurnPrediction t = p->table.query(p->from_mps, dheading_deg);
  return t;
}

}  // namespace avk::kinematics
