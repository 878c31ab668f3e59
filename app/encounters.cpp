#include "app/encounters.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "app/context.hpp"
#include "app/current.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/json_parse.hpp"
#include "mission/document_reader.hpp"
#include "sim/scheduler.hpp"
#include "sim/settle_leg.hpp"
#include "sim/sim_vehicle.hpp"

namespace avk::app {

namespace kin = avk::kinematics;
using nlohmann::json;

namespace {

constexpr double kMaxHorizonS = 600.0;
constexpr double kMaxSpeedMps = 50.0;
constexpr double kMaxAngleDeg = 3600.0;
constexpr double kMaxDistanceM = 100000.0;

// ---- the scenario file ----------------------------------------------------------------------

kin::Contact read_contact(const json& v, const std::string& path,
                          std::vector<mission::FieldError>& errors) {
  kin::Contact c;
  mission::DocumentReader r(v, path, errors);
  r.number("x_m", c.x_m, -kMaxDistanceM, kMaxDistanceM, true);
  r.number("y_m", c.y_m, -kMaxDistanceM, kMaxDistanceM, true);
  r.number("course_deg", c.course_deg, -kMaxAngleDeg, kMaxAngleDeg, true);
  r.number("speed_mps", c.speed_mps, 0.0, kMaxSpeedMps, true);
  r.finish();
  return c;
}

EncounterScenario read_scenario(const json& v, const std::string& path, double file_standoff_m,
                                std::vector<mission::FieldError>& errors) {
  EncounterScenario s;
  s.standoff_m = file_standoff_m;
  mission::DocumentReader r(v, path, errors);
  r.text("name", s.name, true, kMaxScenarioNameBytes);
  if (const json* own = r.get("own", true)) {
    mission::DocumentReader o(*own, r.at("own"), errors);
    o.number("heading_deg", s.own_heading_deg, -kMaxAngleDeg, kMaxAngleDeg, true);
    o.number("speed_mps", s.own_speed_mps, 0.0, kMaxSpeedMps, true, true);
    o.finish();
  }
  if (const json* contacts = r.get("contacts", true)) {
    if (!contacts->is_array() || contacts->empty()) {
      r.error(r.at("contacts"), "expected a non-empty array of contacts");
    } else {
      for (std::size_t k = 0; k < contacts->size(); ++k)
        s.contacts.push_back(
            read_contact((*contacts)[k], r.at("contacts") + "/" + std::to_string(k), errors));
    }
  }
  r.number("standoff_m", s.standoff_m, 0.0, kMaxDistanceM, false, true);
  r.finish();
  return s;
}

// ---- one maneuver flown ---------------------------------------------------------------------

std::optional<Error> check_contacts(const std::vector<kin::Contact>& contacts) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const auto& c = contacts[k];
    const std::string at = "contacts/" + std::to_string(k) + "/";
    if (!std::isfinite(c.x_m) || !std::isfinite(c.y_m))
      return invalid_argument(at + "position", "must be finite");
    if (!std::isfinite(c.course_deg)) return invalid_argument(at + "course_deg", "must be finite");
    if (!(c.speed_mps >= 0.0 && std::isfinite(c.speed_mps)))
      return invalid_argument(at + "speed_mps", "must be >= 0 and finite");
  }
  return std::nullopt;
}

std::optional<Error> check_maneuver(const SimulatedManeuverQuery& q) {
  if (!(q.own_speed_mps > 0.0 && std::isfinite(q.own_speed_mps)))
    return invalid_argument("own_speed", "must be > 0 and finite (m/s)");
  if (!std::isfinite(q.own_heading_deg)) return invalid_argument("own_heading", "must be finite");
  if (!(std::abs(q.dheading_deg) <= 180.0))
    return invalid_argument("dheading", "must be in [-180, 180]");
  if (q.speed_mps && !(*q.speed_mps > 0.0 && std::isfinite(*q.speed_mps)))
    return invalid_argument("speed", "must be > 0 and finite (m/s)");
  if (!(q.horizon_s > 0.0 && q.horizon_s <= kMaxHorizonS))
    return invalid_argument("horizon", "must be > 0 and <= 600 s");
  return check_contacts(q.contacts);
}

// A turn of about 180 deg would go whichever way the heading noise points the controller's
// error; the helm leads such a turn by commanding 90 deg to the chosen side until the vehicle has
// turned 45 deg, then the goal.
constexpr double kLeadAboveDeg = 170.0;
constexpr double kLeadDeg = 90.0;
constexpr double kLeadUntilDeg = 45.0;

}  // namespace

Result<EncounterFile> parse_encounter_file(std::string_view json_text) {
  json doc;
  try {
    doc = kin::parse_json_bounded(json_text);
  } catch (const kin::JsonSyntaxError& e) {
    return invalid_argument(e.pointer(), "the encounter file is not JSON: " + e.reason());
  } catch (const kin::ParseError& e) {
    return invalid_argument(e.field(), "the encounter file is not valid: " + e.message());
  }
  std::vector<mission::FieldError> errors;
  EncounterFile f;
  mission::DocumentReader root(doc, "", errors);
  int version = 0;
  if (root.get("schema_version", true)) {
    root.integer("schema_version", version, 1, 1);
  }
  root.number("standoff_m", f.standoff_m, 0.0, kMaxDistanceM, false, true);
  root.number("horizon_s", f.horizon_s, 0.0, kMaxHorizonS, false, true);
  if (const json* scenarios = root.get("scenarios", true)) {
    if (!scenarios->is_array() || scenarios->empty()) {
      root.error("/scenarios", "expected a non-empty array of scenarios");
    } else {
      std::set<std::string> names;
      for (std::size_t i = 0; i < scenarios->size(); ++i) {
        const std::string path = "/scenarios/" + std::to_string(i);
        f.scenarios.push_back(read_scenario((*scenarios)[i], path, f.standoff_m, errors));
        const std::string& name = f.scenarios.back().name;
        if (!name.empty() && !names.insert(name).second)
          errors.push_back({path + "/name", "duplicate scenario name '" + name + "'"});
      }
    }
  }
  root.finish();
  if (!errors.empty()) {
    Error e = invalid_argument(errors.front().field, "the encounter file is not valid");
    for (const auto& fe : errors)
      e.fields.push_back({fe.field, fe.message});
    return e;
  }
  f.schema_version = version;
  return f;
}

Result<SimulatedManeuver> simulate_maneuver(const SimulatedManeuverQuery& q) {
  if (auto e = check_maneuver(q)) return *e;
  sim::SchedulerOptions so = q.setup.scheduler;
  so.seed = q.seed;
  so.start_time_s = 0.0;
  sim::Scheduler scheduler(so);
  sim::SimVehicleConfig vc = q.setup.vehicle;
  vc.seed = q.seed;
  vc.start_x_m = 0.0;
  vc.start_y_m = 0.0;
  vc.start_heading_deg = q.own_heading_deg;
  vc.start_speed_mps = q.own_speed_mps;
  sim::SimVehicle vehicle(vc, scheduler);

  const sim::SettleRule rule{};
  sim::SettleLeg settle(rule, q.own_speed_mps, q.own_heading_deg);
  const double course = q.own_heading_deg;
  const double speed_after = q.speed_mps.value_or(q.own_speed_mps);
  const double side = q.dheading_deg < 0.0 ? -1.0 : 1.0;
  bool leading = std::abs(q.dheading_deg) > kLeadAboveDeg;
  double turned_deg = 0.0;
  std::optional<double> last_heading;
  std::optional<double> command_s;
  sim::TruthSample at_command{};
  std::vector<sim::TruthSample> truth;

  scheduler.add("helm", q.setup.helm_hz, [&](double now) {
    for (const auto& s : vehicle.take_nav()) {
      if (!command_s) {
        settle.update(s);
      } else if (leading) {
        if (last_heading) turned_deg += kin::angle180_deg(s.heading_deg - *last_heading);
        last_heading = s.heading_deg;
        if (side * turned_deg >= kLeadUntilDeg) leading = false;
      }
    }
    double desired = course;
    double desired_speed = q.own_speed_mps;
    if (!command_s && settle.done(now)) {
      command_s = now;
      at_command = vehicle.truth();
      at_command.t_s = now;
      last_heading = settle.newest()->heading_deg;
    }
    if (command_s) {
      desired = course + (leading ? side * kLeadDeg : q.dheading_deg);
      desired_speed = speed_after;
    }
    vehicle.command({now, kin::wrap360_deg(desired), desired_speed});
  });
  // Ground truth at the navigation rate (the plant's publication rate) after the command.
  scheduler.add("truth", vc.plant_hz, [&](double now) {
    if (!command_s || now <= *command_s) return;
    const sim::TruthSample t = vehicle.truth();
    if (t.t_s > (truth.empty() ? *command_s : truth.back().t_s)) truth.push_back(t);
    if (now >= *command_s + q.horizon_s) scheduler.request_stop();
  });
  scheduler.run_until(rule.max_settle_s + q.horizon_s + 10.0);
  if (!command_s) return internal_error("the simulated vehicle never delivered navigation");

  SimulatedManeuver out;
  out.settle_s = *command_s;
  out.heading_at_command_deg = at_command.heading_deg;
  out.speed_at_command_mps = at_command.speed_over_ground_mps;
  out.track.push_back({0.0, 0.0, 0.0});
  for (const auto& t : truth) {
    out.track.push_back({t.t_s - *command_s, t.x_m - at_command.x_m, t.y_m - at_command.y_m});
  }
  out.min_cpa_m = std::numeric_limits<double>::infinity();
  for (const auto& c : q.contacts) {
    out.cpa.push_back(kin::closest_approach(out.track, c));
    out.min_cpa_m = std::min(out.min_cpa_m, out.cpa.back().distance_m);
  }
  if (q.contacts.empty()) out.min_cpa_m = 0.0;
  return out;
}

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

// ---- the generator --------------------------------------------------------------------------

namespace {

enum class EncounterKind {
  head_on,
  crossing_from_starboard,
  crossing_from_port,
  overtaking,
  overtaken,
  several
};
constexpr EncounterKind kKinds[] = {EncounterKind::head_on,
                                    EncounterKind::crossing_from_starboard,
                                    EncounterKind::crossing_from_port,
                                    EncounterKind::overtaking,
                                    EncounterKind::overtaken,
                                    EncounterKind::several};

const char* kind_name(EncounterKind k) {
  switch (k) {
    case EncounterKind::head_on:
      return "head-on";
    case EncounterKind::crossing_from_starboard:
      return "crossing-from-starboard";
    case EncounterKind::crossing_from_port:
      return "crossing-from-port";
    case EncounterKind::overtaking:
      return "overtaking";
    case EncounterKind::overtaken:
      return "overtaken";
    case EncounterKind::several:
      return "several-contacts";
  }
  return "?";
}

constexpr double kGenStandoffM = 10.0;
constexpr double kGenHorizonS = 120.0;
constexpr double kMinRangeM = 15.0, kMaxRangeM = 80.0;
constexpr double kMinSpeedMps = 0.5, kMaxGenSpeedMps = 1.5;
constexpr double kMinAimS = 15.0, kMaxAimS = 60.0;

// v rounded to 1/per_unit (per_unit whole), so that it prints as short as it reads: 36.3.
double rounded(double v, double per_unit) {
  return std::round(v * per_unit) / per_unit;
}

double course_held_cpa_m(const EncounterScenario& s, const kin::Contact& c) {
  const double h = kin::deg_to_rad(s.own_heading_deg);
  const kin::TimedPath straight{{0.0, 0.0, 0.0},
                                {kGenHorizonS, std::sin(h) * s.own_speed_mps * kGenHorizonS,
                                 std::cos(h) * s.own_speed_mps * kGenHorizonS}};
  return kin::closest_approach(straight, c).distance_m;
}

// A contact of this kind aimed at a point of own track 15-60 s ahead, offset sideways by less
// than the standoff; none when its start falls outside 15-80 m or holding course would clear.
std::optional<kin::Contact> aimed_contact(std::mt19937_64& rng, EncounterKind kind,
                                          const EncounterScenario& s) {
  const auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  const double aim_s = uniform(kMinAimS, kMaxAimS);
  const double offset_m = uniform(-0.6, 0.6) * kGenStandoffM;
  double course = s.own_heading_deg;
  double speed = uniform(kMinSpeedMps, kMaxGenSpeedMps);
  switch (kind) {
    case EncounterKind::head_on:
      course += 180.0 + uniform(-10.0, 10.0);
      break;
    case EncounterKind::crossing_from_starboard:  // comes from the right, heading left
      course += -90.0 + uniform(-30.0, 30.0);
      break;
    case EncounterKind::crossing_from_port:
      course += 90.0 + uniform(-30.0, 30.0);
      break;
    case EncounterKind::overtaking:  // ahead, slower, on the same course
      course += uniform(-10.0, 10.0);
      speed = uniform(kMinSpeedMps, s.own_speed_mps - 0.25);
      break;
    case EncounterKind::overtaken:  // behind, faster
      course += uniform(-10.0, 10.0);
      speed = uniform(s.own_speed_mps + 0.25, kMaxGenSpeedMps);
      break;
    case EncounterKind::several:
      break;
  }
  const double h = kin::deg_to_rad(s.own_heading_deg);
  const double along = s.own_speed_mps * aim_s;
  const double aim_x = std::sin(h) * along + std::cos(h) * offset_m;  // offset to starboard
  const double aim_y = std::cos(h) * along - std::sin(h) * offset_m;
  const double c = kin::deg_to_rad(course);
  kin::Contact out;
  out.course_deg = rounded(kin::wrap360_deg(course), 1.0);
  out.speed_mps = rounded(speed, 20.0);
  out.x_m = rounded(aim_x - std::sin(c) * speed * aim_s, 10.0);
  out.y_m = rounded(aim_y - std::cos(c) * speed * aim_s, 10.0);
  const double range = std::hypot(out.x_m, out.y_m);
  if (range < kMinRangeM || range > kMaxRangeM) return std::nullopt;
  if (out.speed_mps < kMinSpeedMps || out.speed_mps > kMaxGenSpeedMps) return std::nullopt;
  if (!(course_held_cpa_m(s, out) < kGenStandoffM)) return std::nullopt;
  return out;
}

std::string range_text(const kin::Contact& c) {
  return std::to_string(static_cast<int>(std::lround(std::hypot(c.x_m, c.y_m)))) + "m";
}

}  // namespace

Result<EncounterFile> generate_encounters(std::uint64_t seed, int count) {
  if (count < 1 || count > 100000) return invalid_argument("count", "must be 1 to 100000");
  std::mt19937_64 rng(seed);
  EncounterFile f;
  f.standoff_m = kGenStandoffM;
  f.horizon_s = kGenHorizonS;
  constexpr int kMaxTries = 100000;
  for (int i = 0; i < count; ++i) {
    const EncounterKind kind = kKinds[static_cast<std::size_t>(i) % std::size(kKinds)];
    EncounterScenario s;
    s.standoff_m = kGenStandoffM;
    s.own_heading_deg = std::uniform_int_distribution<int>(0, 359)(rng);
    // Overtaking needs a slower contact and being overtaken a faster one, both within 0.5-1.5.
    const double lo = kind == EncounterKind::overtaking ? 0.8 : kMinSpeedMps;
    const double hi = kind == EncounterKind::overtaken ? 1.2 : kMaxGenSpeedMps;
    s.own_speed_mps = rounded(std::uniform_real_distribution<double>(lo, hi)(rng), 20.0);
    const int contacts =
        kind == EncounterKind::several ? std::uniform_int_distribution<int>(2, 3)(rng) : 1;
    for (int k = 0; k < contacts; ++k) {
      const EncounterKind each = kind == EncounterKind::several
                                     ? kKinds[std::uniform_int_distribution<std::size_t>(0, 2)(rng)]
                                     : kind;
      std::optional<kin::Contact> c;
      for (int t = 0; t < kMaxTries && !c; ++t)
        c = aimed_contact(rng, each, s);
      if (!c)
        return internal_error("the generator found no contact for " + std::string(kind_name(kind)));
      s.contacts.push_back(*c);
    }
    const auto nearest = std::min_element(
        s.contacts.begin(), s.contacts.end(), [](const kin::Contact& a, const kin::Contact& b) {
          return std::hypot(a.x_m, a.y_m) < std::hypot(b.x_m, b.y_m);
        });
    char index[8];
    std::snprintf(index, sizeof index, "%02d", i + 1);
    // Appended piece by piece: GCC 12's -Wrestrict misfires on "-" + std::string at -O3.
    s.name = kind_name(kind);
    if (kind == EncounterKind::several) {
      s.name += '-';
      s.name += std::to_string(contacts);
    }
    s.name += "-";
    s.name += range_text(*nearest);
    s.name += "-";
    s.name += index;
    f.scenarios.push_back(std::move(s));
  }
  return f;
}

std::string encounter_file_json(const EncounterFile& file) {
  std::string out = "{\"schema_version\": " + std::to_string(file.schema_version) +
                    ", \"standoff_m\": " + json(file.standoff_m).dump() +
                    ", \"horizon_s\": " + json(file.horizon_s).dump() + ",\n \"scenarios\": [\n";
  for (std::size_t i = 0; i < file.scenarios.size(); ++i) {
    const EncounterScenario& s = file.scenarios[i];
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (const auto& c : s.contacts) {
      contacts.push_back({{"x_m", c.x_m},
                          {"y_m", c.y_m},
                          {"course_deg", c.course_deg},
                          {"speed_mps", c.speed_mps}});
    }
    nlohmann::ordered_json j = {
        {"name", s.name},
        {"own", {{"heading_deg", s.own_heading_deg}, {"speed_mps", s.own_speed_mps}}},
        {"contacts", contacts}};
    if (s.standoff_m != file.standoff_m) j["standoff_m"] = s.standoff_m;
    out += "  " + j.dump() + (i + 1 < file.scenarios.size() ? ",\n" : "\n");
  }
  return out + " ]}\n";
}

}  // namespace avk::app
