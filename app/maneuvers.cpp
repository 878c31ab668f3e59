#include "app/maneuvers.hpp"

#include <cmath>
#include <string>

#include "app/ais_contacts.hpp"
#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/current.hpp"
#include "app/store_access.hpp"
#include "app/traffic.hpp"
#include "app/vehicle_motion.hpp"
#include "app/yaw_rate_table.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/ckt3.hpp"
#include "kinematics/corridor.hpp"
#include "kinematics/position_band.hpp"
#include "kinematics/water_frame.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {

// Limits that keep one request's work bounded (a request is answered on the server's threads).
constexpr double kMaxHorizonS = 600.0;
constexpr std::size_t kMaxContacts = 50;
constexpr std::size_t kMaxCandidates = 721;

bool finite(double v) {
  return std::isfinite(v);
}

// What predicts one candidate: the table, the model or the ray, resolved once per request.
struct Predictor {
  PredictionMethod method = PredictionMethod::avk;
  std::shared_ptr<const kin::MaterializedCkt> fine;
  std::optional<store::StoredModel> model;
  std::optional<std::string> table_source;
  double corridor_share = kin::kDefaultCorridorShare;
  std::optional<double> initial_yaw_rate_dps;        // + clockwise
  std::shared_ptr<const kin::YawRateCkt> yaw_table;  // avk with an initial yaw rate
};

// The yaw rate relative to a candidate: + into it, - against it.
double into_turn_dps(double yaw_rate_dps, double dheading_deg) {
  return dheading_deg < 0.0 ? -yaw_rate_dps : yaw_rate_dps;
}

Result<Predictor> predictor_for(Context& ctx, const std::string& vehicle_id,
                                PredictionMethod method, std::optional<std::int64_t> model_id,
                                double corridor_share,
                                std::optional<double> initial_yaw_rate_dps = std::nullopt) {
  Predictor p;
  p.method = method;
  p.corridor_share = corridor_share;
  p.initial_yaw_rate_dps = initial_yaw_rate_dps;
  if (method == PredictionMethod::avk && initial_yaw_rate_dps) {
    if (auto built = vehicle_yaw_rate_table(ctx, vehicle_id)) {
      p.yaw_table = std::make_shared<const kin::YawRateCkt>(std::move(built->table));
      p.table_source = "turns";
      return p;
    }
  }
  if (method == PredictionMethod::avk) {
    auto t = vehicle_table(ctx, vehicle_id);
    if (!t) return t.error();
    if (!t->fine) return invalid_argument("speed", "the table holds no turn to predict from");
    p.fine = t->fine;
    p.table_source = to_string(t->source);
  } else if (method == PredictionMethod::model) {
    store::Store& db = store_of(ctx);
    p.model = model_id ? db.models().get(*model_id) : db.models().latest(vehicle_id);
    if (!p.model)
      return not_found(model_id ? "no model " + std::to_string(*model_id)
                                : "no model of '" + vehicle_id + "' is stored");
  }
  return p;
}

// One candidate in the normalised frame, timed. `speed_field` names the parameter a speed the
// table cannot answer is reported against.
Result<kin::PredictedManeuver> predict_one(const Predictor& p, double speed_mps,
                                           double dheading_deg, double horizon_s,
                                           const std::string& speed_field) {
  switch (p.method) {
    case PredictionMethod::avk: {
      kin::TurnPrediction t;
      try {
        t = p.yaw_table ? p.yaw_table
                              ->query(speed_mps, dheading_deg,
                                      into_turn_dps(*p.initial_yaw_rate_dps, dheading_deg))
                              .prediction
                        : p.fine->query(speed_mps, dheading_deg);
      } catch (const kin::CktRangeError& e) {
        return invalid_argument(speed_field, e.what());
      }
      return table_maneuver(t, speed_mps, dheading_deg, p.corridor_share);
    }
    case PredictionMethod::model: {
      // The model flown for the whole horizon: its own dynamics settle it on the new heading, and
      // its steps carry their times.
      const kin::YawModel& m = p.model->model;
      kin::PredictOptions o;
      o.steps = static_cast<std::size_t>(std::ceil(horizon_s * m.rate_hz));
      const double d = std::abs(dheading_deg);
      std::vector<kin::PredictedStep> steps;
      try {
        const double rate =
            p.initial_yaw_rate_dps ? into_turn_dps(*p.initial_yaw_rate_dps, dheading_deg) : 0.0;
        const kin::YawHistory h =
            rate == 0.0 ? kin::steady_history(m, 0.0) : kin::turning_history(m, 0.0, rate);
        steps = kin::predict(m, h, d, {0.0, 0.0, 0.0}, speed_mps, o);
      } catch (const std::invalid_argument& e) {
        return internal_error("model " + std::to_string(p.model->id) + ": " + e.what());
      }
      kin::PredictedManeuver out;
      out.dheading_deg = dheading_deg;
      out.speed_mps = speed_mps;
      out.path.reserve(steps.size());
      const double mirror = dheading_deg < 0.0 ? -1.0 : 1.0;
      for (const auto& s : steps) {
        if (!finite(s.x_m) || !finite(s.y_m)) break;
        out.path.push_back({s.t_s, mirror * s.x_m, s.y_m});
      }
      return out;
    }
    case PredictionMethod::instantaneous: {
      return kin::timed_maneuver(dheading_deg, speed_mps,
                                 instantaneous_turn_ray(speed_mps, dheading_deg, horizon_s),
                                 std::nullopt);
    }
  }
  return internal_error("unknown prediction method");
}

std::optional<Error> check(const ManeuverQuery& q) {
  if (!finite(q.own.x_m) || !finite(q.own.y_m))
    return invalid_argument("/own/x_m", "the position must be finite (m)");
  if (!finite(q.own.heading_deg))
    return invalid_argument("/own/heading_deg", "the heading must be finite (deg)");
  if (!finite(q.speed_mps) || !(q.speed_mps > 0.0))
    return invalid_argument("/own/speed_mps", "must be a positive speed (m/s)");
  if (q.contacts.size() > kMaxContacts)
    return invalid_argument("/contacts", "at most " + std::to_string(kMaxContacts) + " contacts");
  for (std::size_t k = 0; k < q.contacts.size(); ++k) {
    const kin::Contact& c = q.contacts[k];
    const std::string at = "/contacts/" + std::to_string(k);
    if (!finite(c.x_m)) return invalid_argument(at + "/x_m", "must be finite (m)");
    if (!finite(c.y_m)) return invalid_argument(at + "/y_m", "must be finite (m)");
    if (!finite(c.course_deg)) return invalid_argument(at + "/course_deg", "must be finite (deg)");
    if (!finite(c.speed_mps) || c.speed_mps < 0.0)
      return invalid_argument(at + "/speed_mps", "must be a speed of 0 or more (m/s)");
  }
  if (!finite(q.standoff_m) || !(q.standoff_m > 0.0))
    return invalid_argument("/standoff_m", "must be a positive distance (m)");
  if (!finite(q.horizon_s) || !(q.horizon_s > 0.0) || q.horizon_s > kMaxHorizonS)
    return invalid_argument("/horizon_s", "must be within (0, " + std::to_string(600) + "] s");
  if (q.candidates_deg.size() > kMaxCandidates)
    return invalid_argument("/candidates_deg",
                            "at most " + std::to_string(kMaxCandidates) + " candidates");
  for (std::size_t k = 0; k < q.candidates_deg.size(); ++k)
    if (!finite(q.candidates_deg[k]) || std::abs(q.candidates_deg[k]) > 180.0)
      return invalid_argument("/candidates_deg/" + std::to_string(k),
                              "must be a heading change within [-180, 180] deg");
  if (q.candidates_deg.empty() && (!finite(q.candidate_step_deg) ||
                                   !(q.candidate_step_deg >= 0.5) || q.candidate_step_deg > 180.0))
    return invalid_argument("/candidate_step_deg", "must be within [0.5, 180] deg");
  if (q.candidate_speed_mps && (!finite(*q.candidate_speed_mps) || !(*q.candidate_speed_mps > 0.0)))
    return invalid_argument("/candidate_speed_mps", "must be a positive speed (m/s)");
  if (!(q.corridor_share > 0.0 && q.corridor_share < 1.0))
    return invalid_argument("/corridor", "must be a share within (0, 1)");
  return std::nullopt;
}

}  // namespace

// The spread of the table's turns at equal time, 1 sigma, per trajectory vertex: across from
// the corridor, along from the turns' timing spread at the commanded speed; both widened for the
// few turns they are known from, as the corridor is (t quantile and sqrt(1 + 1/n) over the normal
// quantile at the same share).
// What the answer assumes of the vehicle's motion: the request's speed reference, else the
// vehicle's; its straight-leg scatter.
AnswerMotion answer_motion(Context& ctx, const std::string& vehicle_id,
                           std::optional<bool> speed_over_ground,
                           std::span<const std::int64_t> missions) {
  AnswerMotion m;
  m.speed_over_ground = kDefaultSpeedReference == kin::SpeedReference::over_ground;
  m.scatter = {kDefaultDriftScatter.along_mps, kDefaultDriftScatter.cross_mps};
  m.position_sd_m = kNavigationPositionSdM;
  if (auto v = vehicle_motion(ctx, vehicle_id, missions)) {
    m.speed_over_ground = v->speed_reference.value == kin::SpeedReference::over_ground;
    m.speed_reference_source = v->speed_reference.source;
    m.scatter = {v->drift_scatter.scatter.along_mps, v->drift_scatter.scatter.cross_mps};
    m.scatter_source = v->drift_scatter.source;
  }
  if (speed_over_ground) {
    m.speed_over_ground = *speed_over_ground;
    m.speed_reference_source = "query";
  }
  return m;
}

kin::PredictedManeuver table_maneuver(const kin::TurnPrediction& t, double speed_mps,
                                      double dheading_deg, double corridor_share) {
  std::vector<double> widths;
  if (t.corridor && t.corridor->n_turns >= 2)
    widths = kin::corridor_half_widths_m(t.trajectory, *t.corridor, corridor_share);
  kin::PredictedManeuver m =
      kin::timed_maneuver(dheading_deg, speed_mps, t.trajectory, t.timing, std::move(widths));
  m.turn_points = m.path.size();
  if (!t.corridor || t.corridor->n_turns < 2) return m;
  constexpr double kZ90 = 1.6448536269514722;  // two-sided 90 % normal quantile
  const double widen = kin::corridor_factor(t.corridor->n_turns, 0.9) / kZ90;
  m.cross_sd_m = kin::corridor_half_widths_m(t.trajectory, *t.corridor, 0.9);
  for (double& w : m.cross_sd_m)
    w /= kZ90;
  if (!t.timing || t.timing->time_sd_s.size() != kin::kTimingStations) return m;
  const std::vector<double> s = kin::cumulative_arc_length_m(t.trajectory);
  const double to_timing = s.back() > 0.0 ? t.timing->length_m / s.back() : 1.0;
  m.along_sd_m.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    m.along_sd_m[i] = widen * m.speed_mps * kin::time_sd_at_length_s(*t.timing, s[i] * to_timing);
  return m;
}

kin::BandSources band_sources(const AnswerMotion& motion,
                              const std::optional<std::array<double, 3>>& current_covariance) {
  kin::BandSources b;
  b.scatter = motion.scatter;
  b.position_sd_m = motion.position_sd_m;
  if (current_covariance) b.current_covariance_m2ps2 = *current_covariance;
  return b;
}

namespace {

// The fleet's other vehicles and the AIS traffic, as straight-line contacts now.
void add_live_contacts(Context& ctx, ManeuverEvaluation& out) {
  for (VehicleLoop* loop : ctx.vehicle_loops()) {
    if (loop->info().id == out.query.vehicle_id) continue;
    const VehicleSnapshot s = loop->snapshot();
    if (!s.nav || s.link == vehicle::LinkState::disconnected) continue;
    kin::Contact c;
    c.x_m = s.nav->x_m;
    c.y_m = s.nav->y_m;
    c.course_deg = s.nav->heading_deg;
    c.speed_mps = s.nav->speed_mps;
    c.position_sd_m = kNavigationPositionSdM;
    out.query.contacts.push_back(c);
    out.live_contact_names.push_back(s.info.id);
  }
  for (const auto& a : traffic(ctx).contacts) {
    const auto c = to_kinematics_contact(a);
    if (!c) continue;
    out.query.contacts.push_back(*c);
    out.live_contact_names.push_back("AIS " + std::to_string(a.mmsi) +
                                     (a.name.empty() ? "" : " " + a.name));
  }
}

}  // namespace

Result<ManeuverEvaluation> evaluate_maneuvers(Context& ctx, const ManeuverQuery& q) {
  if (auto e = check(q)) return *e;
  if (!(q.max_risk >= 0.0 && q.max_risk <= 1.0))
    return invalid_argument("/max_risk", "must be a probability within [0, 1]");
  auto current =
      query_current(ctx, q.vehicle_id, q.current, q.live_current, "/current", q.no_current);
  if (!current) return current.error();
  if (q.initial_yaw_rate_dps &&
      (!finite(*q.initial_yaw_rate_dps) || std::abs(*q.initial_yaw_rate_dps) > 90.0))
    return invalid_argument("/initial_yaw_rate_dps", "must be a yaw rate within [-90, 90] deg/s");
  auto pred = predictor_for(ctx, q.vehicle_id, q.method, q.model_id, q.corridor_share,
                            q.initial_yaw_rate_dps);
  if (!pred) return pred.error();
  ManeuverEvaluation out;
  out.query = q;
  if (q.live_contacts) add_live_contacts(ctx, out);
  out.current = current->current;
  out.current_source = current->source;
  out.frame = current->frame;
  out.current_covariance = current->covariance;
  out.motion = answer_motion(ctx, q.vehicle_id, q.speed_over_ground);
  out.table_source = pred->table_source;
  if (pred->model) out.model_id = pred->model->id;
  const double speed = q.candidate_speed_mps.value_or(q.speed_mps);
  const std::string speed_field = q.candidate_speed_mps ? "/candidate_speed_mps" : "/own/speed_mps";
  const std::vector<double> candidates = q.candidates_deg.empty()
                                             ? kin::candidate_dheadings_deg(q.candidate_step_deg)
                                             : q.candidates_deg;
  kin::ManeuverProblem problem;
  problem.own = q.own;
  problem.contacts = out.query.contacts;
  problem.standoff_m = q.standoff_m;
  problem.horizon_s = q.horizon_s;
  problem.use_corridor = q.use_corridor;
  problem.current = current->current;
  problem.speed_over_ground = out.motion.speed_over_ground;
  // The instantaneous assumption is that the vehicle is on the ray, exactly: it has no band
  // unless asked for one (ray_band), so its risk is 0 or 1 by its CPA.
  if (q.method != PredictionMethod::instantaneous || q.ray_band)
    problem.band = band_sources(out.motion, current->covariance);
  out.candidates.reserve(candidates.size());
  out.timed_by_turns = q.method == PredictionMethod::avk;
  for (const double d : candidates) {
    auto m = predict_one(*pred, speed, d, q.horizon_s, speed_field);
    if (!m) return m.error();
    if (q.method == PredictionMethod::avk && !m->timed_by_turns) out.timed_by_turns = false;
    out.candidates.push_back(kin::evaluate_candidate(problem, *m));
  }
  if (q.corridor_rule) {
    out.chosen = kin::choose_maneuver(out.candidates);
    out.choice.index = out.chosen;
    out.choice.explanation = "the smallest heading change whose corridor edge clears";
    if (out.chosen) {
      const auto& c = out.candidates[*out.chosen];
      out.choice.risk = c.risk;
      out.choice.within_limit = c.risk <= q.max_risk;
      out.choice.margin_m = c.min_cpa_m - q.standoff_m;
    }
  } else {
    out.choice =
        kin::choose_by_risk(problem, q.speed_mps, out.candidates, {q.max_risk, q.prefer_starboard});
    out.chosen = out.choice.index;
  }
  return out;
}

Result<OngoingManeuver> evaluate_ongoing(Context& ctx, const OngoingQuery& q) {
  if (!finite(q.start.x_m) || !finite(q.start.y_m) || !finite(q.start.heading_deg))
    return invalid_argument("x", "the start pose needs finite x, y (m) and heading (deg)");
  if (!finite(q.dheading_deg) || std::abs(q.dheading_deg) > 180.0)
    return invalid_argument("dheading", "must be a heading change within [-180, 180] deg");
  if (!finite(q.speed_mps) || !(q.speed_mps > 0.0))
    return invalid_argument("speed", "must be a positive speed (m/s)");
  if (!finite(q.elapsed_s) || q.elapsed_s < 0.0)
    return invalid_argument("elapsed", "must be a time of 0 s or more");
  if (!finite(q.horizon_s) || !(q.horizon_s > 0.0) || q.horizon_s > kMaxHorizonS)
    return invalid_argument("horizon", "must be within (0, 600] s");
  if (q.measured && (!finite(q.measured->x_m) || !finite(q.measured->y_m)))
    return invalid_argument("mx", "the measured position must be finite (m)");
  if (!(q.corridor_share > 0.0 && q.corridor_share < 1.0))
    return invalid_argument("corridor", "must be a share within (0, 1)");
  auto current =
      query_current(ctx, q.vehicle_id, q.current, q.live_current, "current", q.no_current);
  if (!current) return current.error();
  auto pred = predictor_for(ctx, q.vehicle_id, q.method, q.model_id, q.corridor_share);
  if (!pred) return pred.error();
  auto m = predict_one(*pred, q.speed_mps, q.dheading_deg, q.horizon_s, "speed");
  if (!m) return m.error();
  OngoingManeuver out;
  out.query = q;
  out.current = current->current;
  out.current_source = current->source;
  out.frame = current->frame;
  out.current_covariance = current->covariance;
  out.motion = answer_motion(ctx, q.vehicle_id, q.speed_over_ground);
  const kin::PredictedManeuver whole =
      kin::placed_over_ground(*m, q.start, out.current, out.motion.speed_over_ground, q.horizon_s);
  out.prediction = whole.path;
  out.covariance_m2 =
      kin::position_band(whole.path, whole.along_sd_m, whole.cross_sd_m, whole.turn_points,
                         band_sources(out.motion, current->covariance));
  // As in evaluate_maneuvers, the instantaneous assumption is the ray exactly: no band, and no
  // verdict on whether the vehicle is inside it.
  std::optional<kin::OngoingBand> band;
  if (q.method != PredictionMethod::instantaneous)
    band = kin::OngoingBand{out.covariance_m2, q.corridor_share};
  out.evaluation =
      kin::evaluate_ongoing(out.prediction, whole.half_width_m, q.elapsed_s, q.measured, band);
  out.half_width_m = whole.half_width_m;
  if (pred->model) out.model_id = pred->model->id;
  return out;
}

}  // namespace avk::app
