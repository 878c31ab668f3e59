#include "app/encounters.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <thread>

#include "app/context.hpp"
#include "app/current.hpp"
#include "kinematics/angles.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

// ---- the bench ------------------------------------------------------------------------------

namespace {

struct MethodEvaluations {
  EncounterMethodSummary summary;
  std::vector<ManeuverEvaluation> per_scenario;
};

// One flight's outcome: the actual CPA over the contacts, when, and where the vehicle was then.
struct Flown {
  double min_cpa_m = 0.0;
  double t_cpa_s = 0.0;
  kin::Point at_cpa;
};

// Where a timed path is at t (linear; held at its ends).
kin::Point position_at(const kin::TimedPath& p, double t_s) {
  if (p.empty()) return {};
  if (t_s <= p.front().t_s) return {p.front().x_m, p.front().y_m};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (p[i].t_s < t_s) continue;
    const double dt = p[i].t_s - p[i - 1].t_s;
    const double w = dt > 0.0 ? (t_s - p[i - 1].t_s) / dt : 1.0;
    return {p[i - 1].x_m + w * (p[i].x_m - p[i - 1].x_m),
            p[i - 1].y_m + w * (p[i].y_m - p[i - 1].y_m)};
  }
  return {p.back().x_m, p.back().y_m};
}

using FlownSea = std::vector<std::vector<Flown>>;  // [scenario][flight]

// Every candidate (and the held course, when 0 is not a candidate) of every scenario, flown once
// per sea seed on `threads` threads; each flight writes only its own slot, so the result does not
// depend on the threading.
Result<std::vector<FlownSea>> fly_all(const EncounterFile& file,
                                      const std::vector<double>& flights_deg,
                                      const std::vector<std::uint64_t>& seeds,
                                      const EncounterBenchQuery& q) {
  const std::size_t per = flights_deg.size();
  const std::size_t per_sea = file.scenarios.size() * per;
  const std::size_t jobs = seeds.size() * per_sea;
  std::vector<FlownSea> flown(seeds.size(),
                              FlownSea(file.scenarios.size(), std::vector<Flown>(per)));
  std::vector<std::optional<Error>> failures(jobs);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t j = next++; j < jobs; j = next++) {
      const std::size_t sea = j / per_sea, i = (j % per_sea) / per, k = j % per;
      const EncounterScenario& s = file.scenarios[i];
      SimulatedManeuverQuery mq;
      mq.setup = q.setup;
      mq.seed = seeds[sea];
      mq.own_heading_deg = s.own_heading_deg;
      mq.own_speed_mps = s.own_speed_mps;
      mq.dheading_deg = flights_deg[k];
      mq.contacts = s.contacts;
      mq.horizon_s = file.horizon_s;
      try {
        auto r = simulate_maneuver(mq);
        if (r) {
          Flown& f = flown[sea][i][k];
          f.min_cpa_m = r->min_cpa_m;
          for (const auto& a : r->cpa)
            if (a.distance_m == r->min_cpa_m) f.t_cpa_s = a.time_s;
          f.at_cpa = position_at(r->track, f.t_cpa_s);
        } else {
          failures[j] = r.error();
        }
      } catch (const std::exception& e) {
        failures[j] = internal_error(std::string("simulating a maneuver: ") + e.what());
      }
    }
  };
  std::vector<std::thread> pool;
  const auto n = static_cast<std::size_t>(std::max(1, q.threads));
  for (std::size_t t = 1; t < std::min(n, jobs); ++t)
    pool.emplace_back(work);
  work();
  for (auto& t : pool)
    t.join();
  for (std::size_t j = 0; j < jobs; ++j) {
    if (failures[j]) {
      Error e = *failures[j];
      e.message = file.scenarios[(j % per_sea) / per].name + ": " + e.message;
      return e;
    }
  }
  return flown;
}

// The flown position's error against the predicted path at the same time: along the path's
// direction there (+ ahead) and across it (+ to the right).
std::pair<double, double> along_cross_error_m(const kin::TimedPath& predicted, double t_s,
                                              kin::Point flown) {
  const kin::Point p = position_at(predicted, t_s);
  // The direction: the predicted path's motion over a second around t.
  const kin::Point a = position_at(predicted, t_s - 0.5), b = position_at(predicted, t_s + 0.5);
  double ux = b.x_m - a.x_m, uy = b.y_m - a.y_m;
  const double n = std::hypot(ux, uy);
  if (n > 1e-9) {
    ux /= n, uy /= n;
  } else {
    ux = 0.0, uy = 1.0;
  }
  const double dx = flown.x_m - p.x_m, dy = flown.y_m - p.y_m;
  return {dx * ux + dy * uy, dx * uy - dy * ux};
}

// The calibration of one method's risk over every flown candidate.
std::vector<RiskBin> risk_calibration(const std::vector<std::pair<double, bool>>& risk_violated) {
  constexpr std::size_t bins = std::size(kRiskBinEdges) - 1;
  std::vector<RiskBin> out(bins);
  std::vector<int> violated(bins, 0);
  for (std::size_t b = 0; b < bins; ++b)
    out[b].lo = kRiskBinEdges[b], out[b].hi = std::min(1.0, kRiskBinEdges[b + 1]);
  for (const auto& [risk, v] : risk_violated) {
    std::size_t b = 0;
    while (b + 1 < bins && risk >= kRiskBinEdges[b + 1])
      ++b;
    ++out[b].candidates;
    out[b].mean_predicted += risk;
    violated[b] += v ? 1 : 0;
  }
  for (std::size_t b = 0; b < bins; ++b) {
    if (out[b].candidates == 0) continue;
    out[b].mean_predicted /= out[b].candidates;
    out[b].observed_rate = static_cast<double>(violated[b]) / out[b].candidates;
  }
  return out;
}

ManeuverQuery maneuver_query(const EncounterFile& file, const EncounterScenario& s,
                             const EncounterBenchQuery& q, PredictionMethod method,
                             const std::vector<double>& candidates) {
  ManeuverQuery mq;
  mq.vehicle_id = q.vehicle_id;
  mq.own = kin::Pose{0.0, 0.0, s.own_heading_deg};
  mq.speed_mps = s.own_speed_mps;
  mq.contacts = s.contacts;
  mq.standoff_m = s.standoff_m;
  mq.horizon_s = file.horizon_s;
  mq.candidates_deg = candidates;
  mq.candidate_step_deg = q.candidate_step_deg;
  mq.method = method;
  mq.no_current = !q.use_estimated_current;
  mq.max_risk = q.max_risk;
  mq.prefer_starboard = q.prefer_starboard;
  mq.corridor_rule = q.corridor_rule;
  mq.speed_over_ground = q.speed_over_ground;
  mq.ray_band = q.ray_band;
  return mq;
}

std::optional<double> mean_of(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  double sum = 0.0;
  for (const double x : v)
    sum += x;
  return sum / static_cast<double>(v.size());
}

void summarise(EncounterMethodSummary& m, const std::vector<EncounterScenarioResult>& scenarios,
               std::size_t method_index) {
  std::vector<double> dheadings, errors, abs_errors, along, cross;
  for (const auto& s : scenarios) {
    const EncounterMethodResult& r = s.methods[method_index];
    ++m.scenarios;
    m.violations += r.violation ? 1 : 0;
    m.no_maneuver += r.chosen_dheading_deg ? 0 : 1;
    m.no_maneuver_while_one_existed += r.no_maneuver_while_one_existed ? 1 : 0;
    m.unsafe_while_safe_existed += r.unsafe_while_safe_existed ? 1 : 0;
    if (r.chosen_dheading_deg) dheadings.push_back(std::abs(*r.chosen_dheading_deg));
    if (r.predicted_cpa_m) {
      errors.push_back(*r.predicted_cpa_m - r.actual_cpa_m);
      abs_errors.push_back(std::abs(errors.back()));
    }
    if (r.along_error_m) along.push_back(std::abs(*r.along_error_m));
    if (r.cross_error_m) cross.push_back(std::abs(*r.cross_error_m));
  }
  m.mean_abs_along_error_m = mean_of(along);
  m.mean_abs_cross_error_m = mean_of(cross);
  m.violation_rate = m.scenarios ? static_cast<double>(m.violations) / m.scenarios : 0.0;
  m.mean_abs_dheading_deg = mean_of(dheadings);
  m.mean_cpa_error_m = mean_of(errors);
  m.mean_abs_cpa_error_m = mean_of(abs_errors);
}

}  // namespace

Result<EncounterBench> run_encounter_bench(Context& ctx, const EncounterFile& file,
                                           const EncounterBenchQuery& q) {
  if (q.methods.empty()) return invalid_argument("methods", "name at least one method");
  if (!(q.candidate_step_deg > 0.0 && q.candidate_step_deg <= 180.0))
    return invalid_argument("candidate_step", "must be > 0 and <= 180 deg");
  if (q.threads < 1 || q.threads > 64) return invalid_argument("threads", "must be 1 to 64");
  const std::vector<double> candidates = kin::candidate_dheadings_deg(q.candidate_step_deg);
  // The held course is flown too: what the vehicle does when a method finds nothing.
  std::vector<double> flights_deg = candidates;
  const auto zero = std::find(candidates.begin(), candidates.end(), 0.0);
  const std::size_t held = static_cast<std::size_t>(zero - candidates.begin());
  if (zero == candidates.end()) flights_deg.push_back(0.0);

  // The choices first, on this thread (the database and the table cache are the Context's).
  std::optional<kin::WaterCurrent> current;
  std::vector<MethodEvaluations> methods;
  for (const PredictionMethod m : q.methods) {
    MethodEvaluations me;
    me.summary.method = m;
    for (const auto& s : file.scenarios) {
      ManeuverQuery mq = maneuver_query(file, s, q, m, candidates);
      auto r = evaluate_maneuvers(ctx, mq);
      if (!r) {
        if (me.per_scenario.empty() &&
            (r.error().code == ErrorCode::not_found || r.error().code == ErrorCode::unsupported)) {
          me.summary.available = false;
          me.summary.note = r.error().message;
          break;
        }
        Error e = r.error();
        e.message = s.name + " (" + to_string(m) + "): " + e.message;
        return e;
      }
      if (r->model_id) me.summary.model_id = r->model_id;
      current = r->current;
      me.per_scenario.push_back(std::move(r).value());
    }
    methods.push_back(std::move(me));
  }

  const std::vector<std::uint64_t> seeds =
      q.sea_seeds.empty() ? std::vector<std::uint64_t>{q.seed} : q.sea_seeds;
  auto flown = fly_all(file, flights_deg, seeds, q);
  if (!flown) return flown.error();

  EncounterBench bench;
  bench.current = current;
  bench.flights = seeds.size() * file.scenarios.size() * flights_deg.size();
  std::vector<std::vector<std::pair<double, bool>>> calibration(methods.size());
  for (std::size_t sea = 0; sea < seeds.size(); ++sea) {
    for (std::size_t i = 0; i < file.scenarios.size(); ++i) {
      const EncounterScenario& s = file.scenarios[i];
      const std::vector<Flown>& f = (*flown)[sea][i];
      EncounterScenarioResult sr;
      sr.name = seeds.size() > 1 ? s.name + " @sea " + std::to_string(seeds[sea]) : s.name;
      sr.sea_seed = seeds[sea];
      sr.standoff_m = s.standoff_m;
      sr.candidates_deg = candidates;
      for (std::size_t k = 0; k < candidates.size(); ++k)
        sr.flown_cpa_m.push_back(f[k].min_cpa_m);
      sr.course_held_cpa_m = f[held].min_cpa_m;
      sr.safe_existed = std::any_of(sr.flown_cpa_m.begin(), sr.flown_cpa_m.end(),
                                    [&](double d) { return d >= s.standoff_m; });
      for (std::size_t mi = 0; mi < methods.size(); ++mi) {
        const auto& me = methods[mi];
        if (!me.summary.available) continue;
        const ManeuverEvaluation& ev = me.per_scenario[i];
        for (std::size_t k = 0; k < ev.candidates.size(); ++k)
          calibration[mi].push_back({ev.candidates[k].risk, f[k].min_cpa_m < s.standoff_m});
        EncounterMethodResult r;
        r.method = me.summary.method;
        r.colregs_rule = ev.choice.colregs_rule;
        if (ev.chosen) {
          const auto& c = ev.candidates[*ev.chosen];
          r.chosen_dheading_deg = c.dheading_deg;
          r.predicted_cpa_m = c.min_cpa_m;
          r.predicted_edge_cpa_m = c.min_edge_cpa_m;
          r.chosen_risk = c.risk;
          const Flown& flew = f[*ev.chosen];
          r.actual_cpa_m = flew.min_cpa_m;
          if (!s.contacts.empty()) {
            const auto [along, cross] = along_cross_error_m(c.path, flew.t_cpa_s, flew.at_cpa);
            r.along_error_m = along;
            r.cross_error_m = cross;
          }
        } else {
          r.actual_cpa_m = sr.course_held_cpa_m;
        }
        r.violation = r.actual_cpa_m < s.standoff_m;
        r.no_maneuver_while_one_existed = !ev.chosen && sr.safe_existed;
        r.unsafe_while_safe_existed = ev.chosen && r.violation && sr.safe_existed;
        sr.methods.push_back(r);
      }
      bench.scenarios.push_back(std::move(sr));
    }
  }
  std::size_t index = 0;
  for (std::size_t mi = 0; mi < methods.size(); ++mi) {
    auto& me = methods[mi];
    if (me.summary.available) {
      summarise(me.summary, bench.scenarios, index++);
      me.summary.calibration = risk_calibration(calibration[mi]);
    }
    bench.summary.push_back(me.summary);
  }
  return bench;
}

}  // namespace avk::app
