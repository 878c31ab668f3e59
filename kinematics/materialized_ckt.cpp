#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_blend.hpp"
#include "kinematics/ckt_grid.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

namespace {

// Bracket of v among n values start + k step (the last one capped at end): the lower index and
// the weight of the next; values within 1e-9 of a step of a row snap to it, so a grid point is
// answered by its own cell.
std::pair<std::size_t, double> bracket_of(double v, double start, double step, double end,
                                          std::size_t n) {
  const double x = std::clamp((v - start) / step, 0.0, static_cast<double>(n - 1));
  const std::size_t lo = std::min(n - 1, static_cast<std::size_t>(std::floor(x)));
  if (lo + 1 >= n) return {lo, 0.0};
  const double at_lo = start + static_cast<double>(lo) * step;
  const double at_hi = std::min(end, start + static_cast<double>(lo + 1) * step);
  return {lo, std::clamp((v - at_lo) / (at_hi - at_lo), 0.0, 1.0)};
}

}  // namespace

MaterializedCkt::MaterializedCkt(const Ckt& table, FineGridSpec spec) : spec_(spec) {
  if (!(spec.speed_step_mps > 0.0) || !(spec.dheading_step_deg >= kMinFineDheadingStepDeg) ||
      !std::isfinite(spec.speed_step_mps) || !std::isfinite(spec.dheading_step_deg)) {
    throw std::invalid_argument(
        "fine grid steps must be finite, the speed step positive and the "
        "heading step at least 0.1 deg");
  }
  const auto range = table.speed_range_mps();
  if (!range) throw CktRangeError("the table holds no turns");
  speed_min_mps_ = range->first;
  speed_max_mps_ = range->second;
  pwl_epsilon_m_ = table.options().pwl_epsilon_m;
  // Rows are counted in floating point and capped before any conversion to an integer: a wide
  // speed range overflowed the count (and the index arithmetic that uses it). A last step shorter
  // than the others still gets its row, so the top of the range is a row to blend towards.
  const double span_mps = range->second - range->first;
  const double max_steps = static_cast<double>(kMaxFineSpeedRows - 1);
  if (span_mps / spec_.speed_step_mps > max_steps) spec_.speed_step_mps = span_mps / max_steps;
  speed_count_ = std::min(kMaxFineSpeedRows,
                          static_cast<std::size_t>(std::min(
                              max_steps, std::ceil(span_mps / spec_.speed_step_mps - 1e-9))) +
                              1);
  dheading_count_ = static_cast<std::size_t>(std::ceil(180.0 / spec.dheading_step_deg - 1e-9)) + 1;
  entries_.reserve(speed_count_ * dheading_count_);
  profiles_.reserve(speed_count_ * dheading_count_);
  for (std::size_t i = 0; i < speed_count_; ++i) {
    const double u = row_speed_mps(i);
    for (std::size_t j = 0; j < dheading_count_; ++j)
      entries_.push_back(table.query(u, column_dheading_deg(j)));
    for (std::size_t j = 0; j < dheading_count_; ++j) {
      const TurnPrediction& e = entries_[i * dheading_count_ + j];
      if (j > 0) {
        profiles_.push_back(heading_profile(e.trajectory, column_dheading_deg(j)));
        continue;
      }
      // A turn of 0 deg has no heading profile to blend (every fraction is 0); between 0 and one
      // step the shape is the one-step turn's, as Ckt::query carries its nearest cell's shape.
      HeadingProfile hp =
          heading_profile(entries_[i * dheading_count_ + 1].trajectory, column_dheading_deg(1));
      const auto s = cumulative_arc_length_m(e.trajectory);
      hp.length_m = s.empty() ? 0.0 : s.back();
      profiles_.push_back(std::move(hp));
    }
  }
}

double MaterializedCkt::row_speed_mps(std::size_t row) const {
  return std::min(speed_max_mps_, speed_min_mps_ + static_cast<double>(row) * spec_.speed_step_mps);
}

double MaterializedCkt::column_dheading_deg(std::size_t column) const {
  return std::min(180.0, static_cast<double>(column) * spec_.dheading_step_deg);
}

MaterializedCkt::Bracket MaterializedCkt::speed_bracket(double speed_mps) const {
  const auto [lo, w] =
      bracket_of(speed_mps, speed_min_mps_, spec_.speed_step_mps, speed_max_mps_, speed_count_);
  if (w <= 1e-9) return {lo, lo, 0.0};
  if (w >= 1.0 - 1e-9) return {lo + 1, lo + 1, 0.0};
  return {lo, lo + 1, w};
}

MaterializedCkt::Bracket MaterializedCkt::dheading_bracket(double dheading_deg) const {
  const auto [lo, w] =
      bracket_of(std::abs(dheading_deg), 0.0, spec_.dheading_step_deg, 180.0, dheading_count_);
  if (w <= 1e-9) return {lo, lo, 0.0};
  if (w >= 1.0 - 1e-9) return {lo + 1, lo + 1, 0.0};
  return {lo, lo + 1, w};
}

void MaterializedCkt::check_range(double speed_mps, double dheading_deg) const {
  if (!(speed_mps >= speed_min_mps_ - 0.5 * spec_.speed_step_mps &&
        speed_mps <= speed_max_mps_ + 0.5 * spec_.speed_step_mps) ||
      !(std::abs(dheading_deg) <= 180.0)) {
    throw CktRangeError("speed " + ckt_value_text(speed_mps) + " m/s or heading change " +
                        ckt_value_text(dheading_deg) + " deg is outside the materialised table");
  }
}

MaterializedCkt::Lookup MaterializedCkt::lookup(double speed_mps, double dheading_deg) const {
  check_range(speed_mps, dheading_deg);
  const Bracket r = speed_bracket(speed_mps);
  const Bracket c = dheading_bracket(dheading_deg);
  const std::size_t i = r.weight < 0.5 ? r.lo : r.hi;
  const std::size_t j = c.weight < 0.5 ? c.lo : c.hi;
  return {&entries_[i * dheading_count_ + j], side_of(dheading_deg)};
}

TurnPrediction MaterializedCkt::query(double speed_mps, double dheading_deg) const {
  check_range(speed_mps, dheading_deg);
  const Bracket r = speed_bracket(speed_mps);
  const Bracket c = dheading_bracket(dheading_deg);
  TurnPrediction p;
  if (r.lo == r.hi && c.lo == c.hi) {
    p = entries_[r.lo * dheading_count_ + c.lo];
  } else {
    // Bilinear weights of the (up to) four neighbouring fine cells. Each fine cell is itself
    // Ckt::query's linear blend of table cells, so between two table rows (columns) this is the
    // table's own blend again, up to the simplification of the fine cells' trajectories.
    std::vector<WeightedProfile> sources;
    sources.reserve(4);
    CorridorSources corridors;
    TimingSources timings;
    double length_m = 0.0;
    p.exact_cell = false;
    for (const auto& [i, wi] : {std::pair{r.lo, 1.0 - r.weight}, std::pair{r.hi, r.weight}}) {
      for (const auto& [j, wj] : {std::pair{c.lo, 1.0 - c.weight}, std::pair{c.hi, c.weight}}) {
        const double w = wi * wj;
        if (w <= 0.0) continue;
        const std::size_t k = i * dheading_count_ + j;
        sources.push_back({&profiles_[k], w});
        length_m += w * profiles_[k].length_m;
        p.advance_m += w * entries_[k].advance_m;
        p.transfer_m += w * entries_[k].transfer_m;
        p.extrapolated = p.extrapolated || entries_[k].extrapolated;
        p.short_of_goal = p.short_of_goal || entries_[k].short_of_goal;
        corridors.push_back({&entries_[k].corridor, w});
        timings.push_back({&entries_[k].timing, w});
      }
    }
    p.trajectory = blended_trajectory(sources, length_m, std::abs(dheading_deg), pwl_epsilon_m_);
    p.corridor = blend_corridors(corridors);
    p.timing = blend_timings(timings);
    if (p.timing) p.timing = scaled_timing(*p.timing, arc_length_m(p.trajectory));
  }
  p.speed_mps = speed_mps;
  p.dheading_deg = dheading_deg;
  if (side_of(dheading_deg) == TurnSide::left) p.trajectory = reflect_x(std::move(p.trajectory));
  return p;
}

}  // namespace avk::kinematics
