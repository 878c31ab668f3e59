#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/ckt_blend.hpp"
#include "kinematics/ckt_grid.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

namespace {

// Lead-in plus constant-radius arc fitted to one cell's advance and transfer, used to carry a
// cell's statistics to heading changes outside the table.
AdvanceTransfer arc_model_extrapolate(const CktCell& c, double dheading_deg) {
  const double d0 = deg_to_rad(c.dheading_deg);
  const double d = deg_to_rad(dheading_deg);
  const double radius = c.transfer_m.mean / std::max(1e-9, 1.0 - std::cos(d0));
  const double lead_in = c.advance_m.mean - radius * std::sin(d0);
  return {lead_in + radius * std::sin(d), radius * (1.0 - std::cos(d))};
}

struct RowAnswer {
  std::vector<WeightedProfile> profiles;
  CorridorSources corridors;  // the same cells and weights as profiles
  TimingSources timings;      // likewise
  bool short_of_goal = false;
  double length_m = 0.0;
  AdvanceTransfer at;
  bool exact = false;
  bool extrapolated = false;
};

// The answer within one speed row for |dheading| d: one cell, a blend of the two neighbouring
// cells, or the nearest cell carried beyond the row's range.
RowAnswer answer_row(const std::vector<const CktCell*>& row, double d) {
  RowAnswer a;
  const CktCell* lo = nullptr;
  const CktCell* hi = nullptr;
  for (const CktCell* c : row) {
    if (std::abs(c->dheading_deg - d) <= kCktGridEps) {
      a.profiles.push_back({&c->profile, 1.0});
      a.corridors.push_back({&c->corridor, 1.0});
      a.timings.push_back({&c->timing, 1.0});
      a.short_of_goal = c->short_of_goal;
      a.length_m = c->profile.length_m;
      a.at = {c->advance_m.mean, c->transfer_m.mean};
      a.exact = true;
      return a;
    }
    if (c->dheading_deg < d) lo = c;
    if (c->dheading_deg > d && !hi) hi = c;
  }
  if (lo && hi) {
    const double w = (d - lo->dheading_deg) / (hi->dheading_deg - lo->dheading_deg);
    a.profiles = {{&lo->profile, 1.0 - w}, {&hi->profile, w}};
    a.corridors = {{&lo->corridor, 1.0 - w}, {&hi->corridor, w}};
    a.timings = {{&lo->timing, 1.0 - w}, {&hi->timing, w}};
    a.short_of_goal = lo->short_of_goal || hi->short_of_goal;
    a.length_m = (1.0 - w) * lo->profile.length_m + w * hi->profile.length_m;
    a.at = {(1.0 - w) * lo->advance_m.mean + w * hi->advance_m.mean,
            (1.0 - w) * lo->transfer_m.mean + w * hi->transfer_m.mean};
    return a;
  }
  const CktCell* near = lo ? lo : hi;
  a.extrapolated = true;
  a.profiles = {{&near->profile, 1.0}};
  a.corridors = {{&near->corridor, 1.0}};
  a.timings = {{&near->timing, 1.0}};
  a.short_of_goal = near->short_of_goal;
  a.at = arc_model_extrapolate(*near, d);
  // The turning part grows with the heading change at the cell's radius; the lead-in does not.
  const double radius =
      near->transfer_m.mean / std::max(1e-9, 1.0 - std::cos(deg_to_rad(near->dheading_deg)));
  a.length_m = std::max(near->profile.length_m * 0.25,
                        near->profile.length_m + radius * deg_to_rad(d - near->dheading_deg));
  return a;
}

}  // namespace

void Ckt::drop_observed_turns() {
  for (auto& c : cells_)
    std::vector<TurnSequence>().swap(c.turns);
}

TurnPrediction Ckt::query(double speed_mps, double dheading_deg) const {
  if (!std::isfinite(speed_mps) || !std::isfinite(dheading_deg)) {
    throw std::invalid_argument("speed and heading change must be finite numbers");
  }
  if (dheading_deg < -180.0 || dheading_deg > 180.0) {
    throw CktRangeError("heading change " + ckt_value_text(dheading_deg) +
                        " deg is outside [-180, 180]");
  }
  const auto range = speed_range_mps();
  if (!range) throw CktRangeError("the table holds no turns");
  if (speed_mps < range->first - kCktGridEps || speed_mps > range->second + kCktGridEps) {
    throw CktRangeError("speed " + ckt_value_text(speed_mps) +
                        " m/s is outside the table's range " + ckt_value_text(range->first) + "-" +
                        ckt_value_text(range->second) + " m/s");
  }
  const double d = std::abs(dheading_deg);
  const std::size_t nd = grid_.dheadings_deg.size();
  // Bracketing speed rows among the rows that hold data.
  std::optional<std::size_t> row_lo, row_hi;
  for (std::size_t i = 0; i < grid_.speeds_mps.size(); ++i) {
    bool has = false;
    for (std::size_t j = 0; j < nd && !has; ++j)
      has = cells_[i * nd + j].has_data();
    if (!has) continue;
    if (grid_.speeds_mps[i] <= speed_mps + kCktGridEps) row_lo = i;
    if (grid_.speeds_mps[i] >= speed_mps - kCktGridEps && !row_hi) row_hi = i;
  }
  const auto row_cells = [&](std::size_t i) {
    std::vector<const CktCell*> row;
    for (std::size_t j = 0; j < nd; ++j) {
      if (cells_[i * nd + j].has_data()) row.push_back(&cells_[i * nd + j]);
    }
    return row;
  };
  TurnPrediction p;
  p.speed_mps = speed_mps;
  p.dheading_deg = dheading_deg;
  std::vector<WeightedProfile> profiles;
  CorridorSources corridors;
  TimingSources timings;
  double length_m = 0.0;
  AdvanceTransfer at;
  const RowAnswer a = answer_row(row_cells(*row_lo), d);
  if (*row_lo == *row_hi || std::abs(grid_.speeds_mps[*row_lo] - speed_mps) <= kCktGridEps) {
    profiles = a.profiles;
    corridors = a.corridors;
    timings = a.timings;
    p.short_of_goal = a.short_of_goal;
    length_m = a.length_m;
    at = a.at;
    p.exact_cell = a.exact;
    p.extrapolated = a.extrapolated;
  } else {
    const RowAnswer b = answer_row(row_cells(*row_hi), d);
    const double w = (speed_mps - grid_.speeds_mps[*row_lo]) /
                     (grid_.speeds_mps[*row_hi] - grid_.speeds_mps[*row_lo]);
    for (auto wp : a.profiles)
      profiles.push_back({wp.profile, wp.weight * (1.0 - w)});
    for (auto wp : b.profiles)
      profiles.push_back({wp.profile, wp.weight * w});
    for (auto [c, cw] : a.corridors)
      corridors.push_back({c, cw * (1.0 - w)});
    for (auto [c, cw] : b.corridors)
      corridors.push_back({c, cw * w});
    for (auto [t, tw] : a.timings)
      timings.push_back({t, tw * (1.0 - w)});
    for (auto [t, tw] : b.timings)
      timings.push_back({t, tw * w});
    p.short_of_goal = a.short_of_goal || b.short_of_goal;
    length_m = (1.0 - w) * a.length_m + w * b.length_m;
    at = {(1.0 - w) * a.at.advance_m + w * b.at.advance_m,
          (1.0 - w) * a.at.transfer_m + w * b.at.transfer_m};
    p.extrapolated = a.extrapolated || b.extrapolated;
  }
  if (p.exact_cell) {
    const CktCell& c = cell(*row_lo, *dheading_index(d));
    p.trajectory = c.trajectory;
  } else {
    p.trajectory = blended_trajectory(profiles, length_m, d, options_.pwl_epsilon_m);
  }
  p.advance_m = at.advance_m;
  p.transfer_m = at.transfer_m;
  p.corridor = blend_corridors(corridors);
  // Spanning the answered length: a turn carried beyond the table is longer than its cell, at
  // the cell's mean speed.
  p.timing = blend_timings(timings);
  if (p.timing) p.timing = scaled_timing(*p.timing, arc_length_m(p.trajectory));
  if (dheading_deg < 0.0) p.trajectory = reflect_x(std::move(p.trajectory));
  return p;
}

}  // namespace avk::kinematics
