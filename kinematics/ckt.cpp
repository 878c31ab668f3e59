#include "kinematics/ckt.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "kinematics/angles.hpp"
#include "kinematics/ckt_grid.hpp"
#include "kinematics/mean_turn.hpp"
#include "kinematics/simplify.hpp"
#include "kinematics/turn_measures.hpp"
#include "kinematics/turn_metrics.hpp"

namespace avk::kinematics {

namespace {

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

}  // namespace

std::string ckt_value_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

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
  return nearest_index(grid_.speeds_mps, speed_mps, kCktGridEps);
}

std::optional<std::size_t> Ckt::dheading_index(double dheading_deg) const {
  return nearest_index(grid_.dheadings_deg, dheading_deg, kCktGridEps);
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
      throw std::invalid_argument("CKT heading change " + ckt_value_text(d) +
                                  " deg is outside (0, 180]");
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
      rep.warnings.push_back("cell (" + ckt_value_text(c.speed_mps) + " m/s, " +
                             ckt_value_text(c.dheading_deg) +
                             " deg): its turns changed heading by " + ckt_value_text(observed) +
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
      throw std::invalid_argument("cell (" + ckt_value_text(c.speed_mps) + " m/s, " +
                                  ckt_value_text(c.dheading_deg) +
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

}  // namespace avk::kinematics
