#include "kinematics/ckt3.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kinematics/corridor.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/turn_timing.hpp"

namespace avk::kinematics {

namespace {

constexpr double kRateEps = 1e-9;

std::vector<CellSource> sources_of(const Ckt& table) {
  std::vector<CellSource> out;
  out.reserve(table.cells().size());
  for (const CktCell& c : table.cells())
    out.push_back(c.has_data() ? CellSource::measured : CellSource::interpolated);
  return out;
}

bool answers_speed(const Ckt& table, double speed_mps) {
  const auto r = table.speed_range_mps();
  return r && speed_mps >= r->first - kRateEps && speed_mps <= r->second + kRateEps;
}

}  // namespace

const char* to_string(CellSource s) {
  switch (s) {
    case CellSource::measured:
      return "measured";
    case CellSource::interpolated:
      return "interpolated";
    case CellSource::model:
      return "model";
  }
  return "?";
}

std::optional<CellSource> cell_source_from_string(const std::string& s) {
  for (CellSource c : {CellSource::measured, CellSource::interpolated, CellSource::model})
    if (s == to_string(c)) return c;
  return std::nullopt;
}

double normalized_initial_yaw_rate_dps(const TurnSequence& turn) {
  const auto& r = turn.meta().initial_yaw_rate_dps;
  if (!r) return 0.0;
  if (turn.meta().normalized || turn.side() == TurnSide::right) return *r;
  return -*r;
}

std::vector<double> yaw_rate_grid(const std::vector<TurnSequence>& turns, double match_dps) {
  std::vector<double> rates;
  for (const auto& t : turns)
    if (t.meta().status == TurnStatus::ok) rates.push_back(normalized_initial_yaw_rate_dps(t));
  std::sort(rates.begin(), rates.end());
  std::vector<double> centres{0.0};
  for (std::size_t i = 0; i < rates.size();) {
    std::size_t j = i;
    double sum = 0.0;
    while (j < rates.size() && rates[j] - rates[i] <= 2.0 * match_dps)
      sum += rates[j++];
    const double centre = std::round(2.0 * sum / static_cast<double>(j - i)) / 2.0;
    if (std::abs(centre) > match_dps) centres.push_back(centre);
    i = j;
  }
  std::sort(centres.begin(), centres.end());
  centres.erase(std::unique(centres.begin(), centres.end()), centres.end());
  return centres;
}

YawRateCkt YawRateCkt::build(const std::vector<TurnSequence>& turns,
                             std::optional<std::vector<double>> yaw_rates_dps,
                             const CktOptions& options, std::optional<CktGrid> grid,
                             const YawRateCktOptions& yaw_options, YawRateBuildReport* report) {
  YawRateBuildReport local;
  YawRateBuildReport& rep = report ? *report : local;
  std::vector<double> rates =
      yaw_rates_dps ? *yaw_rates_dps : yaw_rate_grid(turns, yaw_options.yaw_rate_match_dps);
  std::sort(rates.begin(), rates.end());
  if (!grid) grid = grid_of(turns);
  std::vector<std::vector<TurnSequence>> assigned(rates.size());
  for (const auto& t : turns) {
    if (t.meta().status != TurnStatus::ok) continue;
    const double r = normalized_initial_yaw_rate_dps(t);
    std::optional<std::size_t> best;
    for (std::size_t k = 0; k < rates.size(); ++k) {
      const double d = std::abs(rates[k] - r);
      if (d <= yaw_options.yaw_rate_match_dps && (!best || d < std::abs(rates[*best] - r))) {
        best = k;
      }
    }
    if (!best) {
      ++rep.turns_unassigned;
      continue;
    }
    assigned[*best].push_back(t);
    ++rep.turns_used;
  }
  std::vector<YawRateSlice> slices;
  for (std::size_t k = 0; k < rates.size(); ++k) {
    CktBuildReport slice_report;
    Ckt table = Ckt::build(assigned[k], options, grid, &slice_report);
    rep.slices.push_back(std::move(slice_report));
    std::vector<CellSource> sources = sources_of(table);
    slices.push_back({rates[k], std::move(table), std::move(sources)});
  }
  return from_slices(std::move(slices));
}

YawRateCkt YawRateCkt::from_table(Ckt table) {
  std::vector<CellSource> sources = sources_of(table);
  std::vector<YawRateSlice> slices;
  slices.push_back({0.0, std::move(table), std::move(sources)});
  return from_slices(std::move(slices));
}

YawRateCkt YawRateCkt::from_slices(std::vector<YawRateSlice> slices) {
  std::sort(slices.begin(), slices.end(), [](const YawRateSlice& a, const YawRateSlice& b) {
    return a.initial_yaw_rate_dps < b.initial_yaw_rate_dps;
  });
  for (std::size_t k = 0; k < slices.size(); ++k) {
    const YawRateSlice& s = slices[k];
    if (!std::isfinite(s.initial_yaw_rate_dps))
      throw std::invalid_argument("a slice's initial yaw rate must be a finite number");
    if (s.sources.size() != s.table.cells().size()) {
      throw std::invalid_argument("slice " + number_text(s.initial_yaw_rate_dps) + " deg/s has " +
                                  std::to_string(s.sources.size()) + " cell sources for " +
                                  std::to_string(s.table.cells().size()) + " cells");
    }
    if (k > 0 && !(s.table.grid() == slices[0].table.grid())) {
      throw std::invalid_argument("slice " + number_text(s.initial_yaw_rate_dps) +
                                  " deg/s is not on the grid of the other slices");
    }
    if (k > 0 && s.initial_yaw_rate_dps - slices[k - 1].initial_yaw_rate_dps < kRateEps) {
      throw std::invalid_argument("two slices at initial yaw rate " +
                                  number_text(s.initial_yaw_rate_dps) + " deg/s");
    }
  }
  YawRateCkt out;
  out.slices_ = std::move(slices);
  return out;
}

void YawRateCkt::fill(const CellFiller& filler) {
  for (YawRateSlice& s : slices_) {
    std::vector<TurnSequence> model_turns;
    for (const CktCell& c : s.table.cells()) {
      if (c.has_data()) continue;
      if (auto t = filler(c.speed_mps, c.dheading_deg, s.initial_yaw_rate_dps)) {
        model_turns.push_back(std::move(*t));
      }
    }
    if (model_turns.empty()) continue;
    const Ckt filled = Ckt::build(model_turns, s.table.options(), s.table.grid());
    std::vector<CktCell> cells = s.table.cells();
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (cells[i].has_data() || !filled.cells()[i].has_data()) continue;
      cells[i] = filled.cells()[i];
      s.sources[i] = CellSource::model;
    }
    Ckt table = Ckt::from_cells(s.table.grid(), std::move(cells), s.table.options());
    table.vehicle_id = s.table.vehicle_id;
    table.vehicle_length_m = s.table.vehicle_length_m;
    table.created_utc = s.table.created_utc;
    s.table = std::move(table);
  }
}

const YawRateSlice* YawRateCkt::steady() const {
  for (const auto& s : slices_)
    if (std::abs(s.initial_yaw_rate_dps) <= kRateEps) return &s;
  return nullptr;
}

std::vector<SliceCoverage> YawRateCkt::coverage() const {
  std::vector<SliceCoverage> out;
  for (const auto& s : slices_) {
    SliceCoverage c;
    c.initial_yaw_rate_dps = s.initial_yaw_rate_dps;
    for (CellSource src : s.sources) {
      if (src == CellSource::measured) ++c.measured;
      if (src == CellSource::model) ++c.model;
      if (src == CellSource::interpolated) ++c.empty;
    }
    out.push_back(c);
  }
  return out;
}

YawRatePrediction YawRateCkt::query(double speed_mps, double dheading_deg,
                                    double initial_yaw_rate_dps) const {
  if (!std::isfinite(initial_yaw_rate_dps))
    throw std::invalid_argument("the initial yaw rate must be a finite number");
  if (slices_.empty()) throw CktRangeError("the table holds no turns");
  // The slices that can answer this speed; the others take no part.
  std::vector<const YawRateSlice*> usable;
  for (const auto& s : slices_)
    if (answers_speed(s.table, speed_mps)) usable.push_back(&s);
  if (usable.empty()) {
    // Let the steady (or first) slice say why.
    (steady() ? steady() : &slices_.front())->table.query(speed_mps, dheading_deg);
    throw CktRangeError("speed " + number_text(speed_mps) + " m/s is outside every slice's range");
  }
  YawRatePrediction out;
  out.initial_yaw_rate_dps = initial_yaw_rate_dps;
  const YawRateSlice* lo = usable.front();
  const YawRateSlice* hi = usable.front();
  double w = 0.0;
  if (initial_yaw_rate_dps < usable.front()->initial_yaw_rate_dps - kRateEps) {
    out.yaw_rate_clamped = true;
  } else if (initial_yaw_rate_dps > usable.back()->initial_yaw_rate_dps + kRateEps) {
    out.yaw_rate_clamped = true;
    lo = hi = usable.back();
  } else {
    for (std::size_t k = 0; k < usable.size(); ++k) {
      const double r = usable[k]->initial_yaw_rate_dps;
      if (std::abs(r - initial_yaw_rate_dps) <= kRateEps) {
        lo = hi = usable[k];
        break;
      }
      if (r < initial_yaw_rate_dps) lo = usable[k];
      if (r > initial_yaw_rate_dps) {
        hi = usable[k];
        w = (initial_yaw_rate_dps - lo->initial_yaw_rate_dps) /
            (hi->initial_yaw_rate_dps - lo->initial_yaw_rate_dps);
        break;
      }
    }
  }
  const double d = std::abs(dheading_deg);
  if (lo == hi) {
    out.prediction = lo->table.query(speed_mps, dheading_deg);
    if (out.prediction.exact_cell) {
      const std::size_t nd = lo->table.grid().dheadings_deg.size();
      const auto i = lo->table.speed_index(speed_mps);
      const auto j = lo->table.dheading_index(d);
      if (i && j) out.source = lo->sources[*i * nd + *j];
    }
    return out;
  }
  // Between two slices: blend their right-turn answers as Ckt::query blends heading changes.
  const TurnPrediction a = lo->table.query(speed_mps, d);
  const TurnPrediction b = hi->table.query(speed_mps, d);
  const HeadingProfile pa = heading_profile(a.trajectory, d);
  const HeadingProfile pb = heading_profile(b.trajectory, d);
  TurnPrediction& p = out.prediction;
  p.speed_mps = speed_mps;
  p.dheading_deg = dheading_deg;
  const double length_m = (1.0 - w) * pa.length_m + w * pb.length_m;
  p.trajectory = blended_trajectory({{&pa, 1.0 - w}, {&pb, w}}, length_m, d,
                                    lo->table.options().pwl_epsilon_m);
  p.advance_m = (1.0 - w) * a.advance_m + w * b.advance_m;
  p.transfer_m = (1.0 - w) * a.transfer_m + w * b.transfer_m;
  p.exact_cell = false;
  p.extrapolated = a.extrapolated || b.extrapolated;
  p.short_of_goal = a.short_of_goal || b.short_of_goal;
  p.corridor = blend_corridors({{&a.corridor, 1.0 - w}, {&b.corridor, w}});
  p.timing = blend_timings({{&a.timing, 1.0 - w}, {&b.timing, w}});
  if (p.timing) p.timing = scaled_timing(*p.timing, arc_length_m(p.trajectory));
  if (dheading_deg < 0.0) p.trajectory = reflect_x(std::move(p.trajectory));
  return out;
}

}  // namespace avk::kinematics
