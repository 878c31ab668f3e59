#include "kinematics/ckt.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "kinematics/angles.hpp"
#include "kinematics/mean_turn.hpp"
#include "kinematics/simplify.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_metrics.hpp"

namespace avk::kinematics {

namespace {

constexpr double kGridEps = 1e-9;

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

std::vector<double> distinct_sorted(std::vector<double> v, double quantum) {
  for (double& x : v)
    x = std::round(x / quantum) * quantum;
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(), [&](double a, double b) { return b - a < quantum / 2; }),
          v.end());
  return v;
}

std::optional<std::size_t> nearest_index(const std::vector<double>& values, double v, double tol) {
  std::optional<std::size_t> best;
  double best_d = tol;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double d = std::abs(values[i] - v);
    if (d <= best_d) {
      best = i;
      best_d = d;
    }
  }
  return best;
}

// A profile blended from several cells with weights; reconstructs the trajectory of a turn of
// `dheading_deg` from it. Breakpoints are the union of the sources' breakpoints so one source
// with weight 1 reproduces its trajectory exactly.

Polyline reconstruct(const std::vector<WeightedProfile>& sources, double length_m,
                     double dheading_deg) {
  std::vector<double> breaks;
  for (const auto& s : sources)
    breaks.insert(breaks.end(), s.profile->breaks.begin(), s.profile->breaks.end());
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<std::size_t> cursor(sources.size(), 0);
  Polyline out;
  out.reserve(breaks.size());
  Point p{0.0, 0.0};
  out.push_back(p);
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    const double mid = 0.5 * (breaks[j] + breaks[j + 1]);
    double fraction = 0.0;
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const HeadingProfile& hp = *sources[i].profile;
      while (cursor[i] + 1 < hp.fraction.size() && hp.breaks[cursor[i] + 1] <= mid)
        ++cursor[i];
      fraction += sources[i].weight * hp.fraction[cursor[i]];
    }
    const double heading = deg_to_rad(fraction * dheading_deg);
    const double ds = (breaks[j + 1] - breaks[j]) * length_m;
    p = {p.x_m + ds * std::sin(heading), p.y_m + ds * std::cos(heading)};
    out.push_back(p);
  }
  return out;
}

// Lead-in plus constant-radius arc fitted to one cell's advance and transfer, used to carry a
// cell's statistics to heading changes outside the table.
AdvanceTransfer arc_model_extrapolate(const CktCell& c, double dheading_deg) {
  const double d0 = deg_to_rad(c.dheading_deg);
  const double d = deg_to_rad(dheading_deg);
  const double radius = c.transfer_m.mean / std::max(1e-9, 1.0 - std::cos(d0));
  const double lead_in = c.advance_m.mean - radius * std::sin(d0);
  return {lead_in + radius * std::sin(d), radius * (1.0 - std::cos(d))};
}

}  // namespace

// A blend's trajectory as a query answers it: reconstructed, then thinned to the table's
// tolerance (the blend has the union of its sources' vertices) keeping the final segment, which
// carries the goal heading.
Polyline blended_trajectory(const std::vector<WeightedProfile>& sources, double length_m,
                            double dheading_deg, double pwl_epsilon_m) {
  Polyline full = reconstruct(sources, length_m, dheading_deg);
  const Point last = full.back();
  full.pop_back();
  Polyline out = full.size() > 2 ? simplify_polyline(full, pwl_epsilon_m) : full;
  out.push_back(last);
  return out;
}

const char* to_string(MeanKind k) {
  return k == MeanKind::arc_length ? "arc_length" : "x_grid";
}

std::optional<MeanKind> mean_kind_from_string(const std::string& s) {
  if (s == "arc_length") return MeanKind::arc_length;
  if (s == "x_grid") return MeanKind::x_grid;
  return std::nullopt;
}

MeanSd mean_sd(const std::vector<double>& values) {
  MeanSd r;
  if (values.empty()) return r;
  r.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  if (values.size() > 1) {
    double ss = 0.0;
    for (double v : values)
      ss += (v - r.mean) * (v - r.mean);
    r.sd = std::sqrt(ss / static_cast<double>(values.size() - 1));
  }
  return r;
}

HeadingProfile heading_profile(const Polyline& trajectory, double goal_dheading_deg) {
  HeadingProfile hp;
  const std::vector<double> s = cumulative_arc_length_m(trajectory);
  hp.length_m = s.empty() ? 0.0 : s.back();
  if (trajectory.size() < 2 || !(hp.length_m > 0.0) || goal_dheading_deg == 0.0) {
    hp.breaks = {0.0, 1.0};
    hp.fraction = {0.0};
    return hp;
  }
  // Each segment's heading is taken within 180 deg of the turn's mid-heading (see the header),
  // on its own: no segment's choice depends on another's, so a noisy one cannot shift the rest.
  const double mid_deg = 0.5 * goal_dheading_deg;
  hp.breaks.push_back(0.0);
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double len = s[i] - s[i - 1];
    if (len <= 0.0) continue;
    const double h = heading_of_deg(trajectory[i].x_m - trajectory[i - 1].x_m,
                                    trajectory[i].y_m - trajectory[i - 1].y_m);
    const double change = mid_deg + angle180_deg(h - mid_deg);
    hp.fraction.push_back(change / goal_dheading_deg);
    hp.breaks.push_back(s[i] / hp.length_m);
  }
  hp.breaks.back() = 1.0;
  return hp;
}

const CktCell& Ckt::cell(std::size_t speed_index, std::size_t dheading_index) const {
  return cells_.at(speed_index * grid_.dheadings_deg.size() + dheading_index);
}

std::optional<std::size_t> Ckt::speed_index(double speed_mps) const {
  return nearest_index(grid_.speeds_mps, speed_mps, kGridEps);
}

std::optional<std::size_t> Ckt::dheading_index(double dheading_deg) const {
  return nearest_index(grid_.dheadings_deg, dheading_deg, kGridEps);
}

const char* to_string(TableFrame f) {
  switch (f) {
    case TableFrame::ground:
      return "ground";
    case TableFrame::water:
      return "water";
    case TableFrame::mixed:
      return "mixed";
  }
  return "ground";
}

std::optional<TableFrame> table_frame_from_string(const std::string& s) {
  for (TableFrame f : {TableFrame::ground, TableFrame::water, TableFrame::mixed})
    if (s == to_string(f)) return f;
  return std::nullopt;
}

CktGrid grid_of(const std::vector<TurnSequence>& turns) {
  std::vector<double> speeds, dheadings;
  for (const auto& t : turns) {
    if (t.meta().status != TurnStatus::ok || t.meta().speed_after_mps) continue;
    speeds.push_back(t.meta().commanded_speed_mps);
    dheadings.push_back(std::abs(t.meta().goal_dheading_deg));
  }
  return CktGrid{distinct_sorted(speeds, 0.01), distinct_sorted(dheadings, 0.1)};
}

Ckt Ckt::build(const std::vector<TurnSequence>& turns, const CktOptions& options,
               std::optional<CktGrid> grid, CktBuildReport* report) {
  CktBuildReport local;
  CktBuildReport& rep = report ? *report : local;
  if (!grid) grid = grid_of(turns);
  for (double d : grid->dheadings_deg) {
    if (!(d > 0.0 && d <= 180.0)) {
      throw std::invalid_argument("CKT heading change " + fmt(d) + " deg is outside (0, 180]");
    }
  }
  Ckt table;
  table.grid_ = *grid;
  table.options_ = options;
  const std::size_t ns = grid->speeds_mps.size(), nd = grid->dheadings_deg.size();
  table.cells_.resize(ns * nd);
  for (std::size_t i = 0; i < ns; ++i) {
    for (std::size_t j = 0; j < nd; ++j) {
      table.cells_[i * nd + j].speed_mps = grid->speeds_mps[i];
      table.cells_[i * nd + j].dheading_deg = grid->dheadings_deg[j];
    }
  }
  // This call's own counts: a report passed in may already hold another build's.
  std::size_t used = 0, water = 0;
  for (const auto& t : turns) {
    if (t.meta().status != TurnStatus::ok) {
      ++rep.turns_skipped_status;
      continue;
    }
    if (t.meta().speed_after_mps) {
      ++rep.turns_speed_change;
      continue;
    }
    const auto si =
        nearest_index(grid->speeds_mps, t.meta().commanded_speed_mps, options.speed_match_mps);
    const auto di = nearest_index(grid->dheadings_deg, std::abs(t.meta().goal_dheading_deg),
                                  options.dheading_match_deg);
    if (!si || !di) {
      ++rep.turns_unassigned;
      continue;
    }
    table.cells_[*si * nd + *di].turns.push_back(t.normalized());
    ++rep.turns_used;
    ++used;
    if (t.meta().removed_current) {
      ++rep.turns_water_frame;
      ++water;
    }
  }
  table.frame = water == 0      ? TableFrame::ground
                : water == used ? TableFrame::water
                                : TableFrame::mixed;
  for (CktCell& c : table.cells_) {
    c.n_turns = c.turns.size();
    if (c.turns.empty()) continue;
    std::vector<Polyline> paths;
    std::vector<double> advances, transfers;
    paths.reserve(c.turns.size());
    for (const auto& t : c.turns) {
      paths.push_back(t.points());
      const AdvanceTransfer at = advance_transfer(paths.back());
      advances.push_back(at.advance_m);
      transfers.push_back(at.transfer_m);
    }
    c.advance_m = mean_sd(advances);
    c.transfer_m = mean_sd(transfers);
    if (paths.size() >= 2) {
      c.avk_error_m2 =
          cell_errors(paths, c.dheading_deg, {options.mean_x_step_m, 0.0}).avk_error_m2;
    }
    std::vector<StationedPath> stationed;
    stationed.reserve(c.turns.size());
    double observed = 0.0;
    for (const auto& t : c.turns) {
      stationed.push_back(stationed_by_time(t));
      observed += std::abs(t.meta().observed_dheading_deg) / static_cast<double>(c.turns.size());
    }
    c.short_of_goal = observed < kShortOfGoalFraction * c.dheading_deg;
    if (c.short_of_goal) {
      rep.warnings.push_back("cell (" + fmt(c.speed_mps) + " m/s, " + fmt(c.dheading_deg) +
                             " deg): its turns changed heading by " + fmt(observed) +
                             " deg on average; past that the trajectory is extended, not seen");
    }
    const StationedPath arc_mean = mean_path_at_stations(stationed, c.dheading_deg);
    c.corridor = corridor_of(stationed, arc_mean, c.dheading_deg);
    if (options.mean_kind == MeanKind::arc_length) {
      c.mean_turn = arc_mean.points;
      // Run on along the goal heading past the longest turn, as the x-grid mean runs past the
      // largest x, so the fit ends on the goal heading.
      const Point last = c.mean_turn.back();
      const double g = deg_to_rad(c.dheading_deg);
      c.mean_turn.push_back({last.x_m + options.mean_x_margin_m * std::sin(g),
                             last.y_m + options.mean_x_margin_m * std::cos(g)});
    } else {
      c.mean_turn =
          mean_turn(paths, c.dheading_deg, {options.mean_x_step_m, options.mean_x_margin_m})
              .points();
    }
    c.fit = fit_curve(options.fit_kind, c.mean_turn);
    c.trajectory = piecewise_linear(c.fit, options.pwl_epsilon_m);
    // Every normalised turn starts at the origin; the fit misses it by its residual, and a
    // y = f(x) fit cannot hold the straight lead-in at all (then the origin is a new vertex).
    if (!c.trajectory.empty()) {
      if (distance_m(c.trajectory.front(), {0.0, 0.0}) > options.pwl_epsilon_m) {
        c.trajectory.insert(c.trajectory.begin(), Point{0.0, 0.0});
      } else {
        c.trajectory.front() = {0.0, 0.0};
      }
    }
    // The fit rounds off the corner where the mean turn runs onto its goal ray; the trajectory
    // ends with an explicit segment on the goal heading so it (and every blend of it) ends there.
    if (c.trajectory.size() >= 2) {
      const Point& a = c.trajectory[c.trajectory.size() - 2];
      const Point& b = c.trajectory.back();
      const double end_heading = heading_of_deg(b.x_m - a.x_m, b.y_m - a.y_m);
      if (std::abs(angle180_deg(end_heading - c.dheading_deg)) > 1e-6) {
        const double goal = deg_to_rad(c.dheading_deg);
        const double tail = std::max(options.mean_x_margin_m, 4.0 * options.pwl_epsilon_m);
        c.trajectory.push_back({b.x_m + tail * std::sin(goal), b.y_m + tail * std::cos(goal)});
      }
    }
    c.profile = heading_profile(c.trajectory, c.dheading_deg);
    c.timing = timing_of(arc_mean, c.speed_mps, c.trajectory);
    // How far ahead or behind the mean the turns ran: the same projection, turn by turn.
    if (c.timing) c.timing->time_sd_s = timing_spread_s(stationed, c.speed_mps, c.trajectory);
  }
  return table;
}

Ckt Ckt::from_cells(CktGrid grid, std::vector<CktCell> cells, CktOptions options) {
  Ckt table;
  const std::size_t ns = grid.speeds_mps.size(), nd = grid.dheadings_deg.size();
  table.grid_ = std::move(grid);
  table.options_ = options;
  table.cells_.resize(ns * nd);
  for (std::size_t i = 0; i < ns; ++i) {
    for (std::size_t j = 0; j < nd; ++j) {
      table.cells_[i * nd + j].speed_mps = table.grid_.speeds_mps[i];
      table.cells_[i * nd + j].dheading_deg = table.grid_.dheadings_deg[j];
    }
  }
  for (CktCell& c : cells) {
    const auto si = table.speed_index(c.speed_mps);
    const auto di = table.dheading_index(c.dheading_deg);
    if (!si || !di) {
      throw std::invalid_argument("cell (" + fmt(c.speed_mps) + " m/s, " + fmt(c.dheading_deg) +
                                  " deg) is not on the table's grid");
    }
    c.profile = heading_profile(c.trajectory, c.dheading_deg);
    table.cells_[*si * nd + *di] = std::move(c);
  }
  return table;
}

std::optional<std::pair<double, double>> Ckt::speed_range_mps() const {
  std::optional<std::pair<double, double>> r;
  const std::size_t nd = grid_.dheadings_deg.size();
  for (std::size_t i = 0; i < grid_.speeds_mps.size(); ++i) {
    for (std::size_t j = 0; j < nd; ++j) {
      if (!cells_[i * nd + j].has_data()) continue;
      const double u = grid_.speeds_mps[i];
      if (!r) r = {u, u};
      r->first = std::min(r->first, u);
      r->second = std::max(r->second, u);
      break;
    }
  }
  return r;
}

namespace {

using CorridorSources = std::vector<std::pair<const std::optional<Corridor>*, double>>;
using TimingSources = std::vector<std::pair<const std::optional<TurnTiming>*, double>>;

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
    if (std::abs(c->dheading_deg - d) <= kGridEps) {
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
    throw CktRangeError("heading change " + fmt(dheading_deg) + " deg is outside [-180, 180]");
  }
  const auto range = speed_range_mps();
  if (!range) throw CktRangeError("the table holds no turns");
  if (speed_mps < range->first - kGridEps || speed_mps > range->second + kGridEps) {
    throw CktRangeError("speed " + fmt(speed_mps) + " m/s is outside the table's range " +
                        fmt(range->first) + "-" + fmt(range->second) + " m/s");
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
    if (grid_.speeds_mps[i] <= speed_mps + kGridEps) row_lo = i;
    if (grid_.speeds_mps[i] >= speed_mps - kGridEps && !row_hi) row_hi = i;
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
  if (*row_lo == *row_hi || std::abs(grid_.speeds_mps[*row_lo] - speed_mps) <= kGridEps) {
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
    throw CktRangeError("speed " + fmt(speed_mps) + " m/s or heading change " + fmt(dheading_deg) +
                        " deg is outside the materialised table");
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
