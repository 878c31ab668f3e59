#include "app/predict.hpp"
#include "app/table_cache.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/current.hpp"
#include "app/maneuvers.hpp"
#include "app/store_access.hpp"
#include "app/yaw_rate_table.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/retimed_turn.hpp"
#include "kinematics/water_frame.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

const char* to_string(PredictionMethod m) {
  switch (m) {
    case PredictionMethod::avk:
      return "avk";
    case PredictionMethod::model:
      return "model";
    case PredictionMethod::instantaneous:
      return "instantaneous";
  }
  return "avk";
}

std::optional<PredictionMethod> prediction_method_from_string(const std::string& s) {
  for (const auto m :
       {PredictionMethod::avk, PredictionMethod::model, PredictionMethod::instantaneous})
    if (s == to_string(m)) return m;
  return std::nullopt;
}

const char* to_string(SpeedChangeSource s) {
  switch (s) {
    case SpeedChangeSource::measured:
      return "measured";
    case SpeedChangeSource::retimed:
      return "retimed";
    case SpeedChangeSource::model:
      return "model";
  }
  return "retimed";
}

kin::Polyline instantaneous_turn_ray(double speed_mps, double dheading_deg, double duration_s) {
  const kin::Point d = kin::rotate_by_heading({0.0, speed_mps * duration_s}, dheading_deg);
  return {{0.0, 0.0}, d};
}

namespace {

Result<Prediction> from_table(Prediction p, kin::TurnPrediction t);

constexpr double kMaxInitialYawRateDps = 90.0;

// One error naming every parameter in `problems` (not empty), the first as its field.
Error parameters_error(std::vector<FieldError> problems) {
  Error e = invalid_argument(problems.front().field, problems.front().message);
  if (problems.size() > 1) e.fields = std::move(problems);
  return e;
}

// The speed outside the table's speed range, named with the range; none within it.
std::optional<FieldError> table_speed_problem(const kin::Ckt& table, double speed_mps) {
  const auto range = table.speed_range_mps();
  if (!range || !std::isfinite(speed_mps) ||
      (speed_mps >= range->first && speed_mps <= range->second))
    return std::nullopt;
  return FieldError{"speed", kin::number_text(speed_mps) +
                                 " m/s is outside the table's speed range [" +
                                 kin::number_text(range->first) + ", " +
                                 kin::number_text(range->second) + "] m/s"};
}

// The table could not answer (kinematics::CktRangeError `what`): each parameter outside the
// table's range, named with the range, so a client fixes both at once when both are off.
Error table_range_error(const kin::Ckt& table, const PredictQuery& q, const std::string& what) {
  std::vector<FieldError> problems;
  if (auto speed = table_speed_problem(table, q.speed_mps)) problems.push_back(std::move(*speed));
  if (!(std::abs(q.dheading_deg) <= 180.0))
    problems.push_back({"dheading", kin::number_text(q.dheading_deg) +
                                        " deg is outside the table's heading changes [-180, 180] "
                                        "deg"});
  if (problems.empty()) problems.push_back({"speed", what});
  return parameters_error(std::move(problems));
}

// Speed and heading change are checked together, so an answer names both when both are off.
std::vector<FieldError> turn_problems(const PredictQuery& q) {
  std::vector<FieldError> problems;
  if (!std::isfinite(q.speed_mps) || !(q.speed_mps > 0.0))
    problems.push_back({"speed", "must be a positive speed (m/s)"});
  if (!std::isfinite(q.dheading_deg) || q.dheading_deg == 0.0 || std::abs(q.dheading_deg) > 180.0)
    problems.push_back({"dheading", "must be in [-180, 0) or (0, 180] degrees"});
  return problems;
}

// A bad heading change with a speed the table does not cover: both named, the speed with the
// table's range (the table is looked at only when the request is wrong already).
Error turn_error(std::vector<FieldError> problems, const kin::Ckt* table, double speed_mps) {
  const bool speed_named = std::any_of(problems.begin(), problems.end(),
                                       [](const FieldError& f) { return f.field == "speed"; });
  if (table && !speed_named) {
    if (auto speed = table_speed_problem(*table, speed_mps))
      problems.insert(problems.begin(), std::move(*speed));
  }
  return parameters_error(std::move(problems));
}

std::optional<Error> check(const PredictQuery& q) {
  if (auto problems = turn_problems(q); !problems.empty())
    return parameters_error(std::move(problems));
  if (q.pose && !(std::isfinite(q.pose->x_m) && std::isfinite(q.pose->y_m) &&
                  std::isfinite(q.pose->heading_deg)))
    return invalid_argument("x", "a pose needs finite x, y and heading");
  if (!(q.corridor_share > 0.0 && q.corridor_share < 1.0))
    return invalid_argument("corridor", "must be a share within (0, 1)");
  if (q.speed_after_mps && !(std::isfinite(*q.speed_after_mps) && *q.speed_after_mps > 0.0))
    return invalid_argument("speed_after", "must be a positive speed (m/s)");
  if (q.initial_yaw_rate_dps && (!std::isfinite(*q.initial_yaw_rate_dps) ||
                                 std::abs(*q.initial_yaw_rate_dps) > kMaxInitialYawRateDps))
    return invalid_argument("initial_yaw_rate", "must be a yaw rate within [-90, 90] deg/s");
  return std::nullopt;
}

// A speed after equal to the speed before is no speed change.
PredictQuery without_null_change(PredictQuery q) {
  if (q.speed_after_mps && std::abs(*q.speed_after_mps - q.speed_mps) < 1e-9)
    q.speed_after_mps.reset();
  return q;
}

// The yaw rate relative to the turn: + into it (towards its side), - against it.
double into_turn_dps(double yaw_rate_dps, double dheading_deg) {
  return dheading_deg < 0.0 ? -yaw_rate_dps : yaw_rate_dps;
}

// avk with an initial yaw rate: the vehicle's table over the initial yaw rate (its turns, the
// empty cells filled by its latest model), or its imported table as the steady slice.
Result<Prediction> from_yaw_rate_table(Context& ctx, Prediction p) {
  const PredictQuery& q = p.query;
  kin::YawRateCkt table;
  auto built = vehicle_yaw_rate_table(ctx, q.vehicle_id);
  if (built) {
    table = std::move(built->table);
    p.table_source = "turns";
  } else {
    auto t = vehicle_table(ctx, q.vehicle_id);
    if (!t) return t.error();
    table = kin::YawRateCkt::from_table(*t->table);
    p.table_source = to_string(t->source);
    p.snapshot_id = t->snapshot_id;
  }
  try {
    kin::YawRatePrediction a = table.query(q.speed_mps, q.dheading_deg,
                                           into_turn_dps(*q.initial_yaw_rate_dps, q.dheading_deg));
    p.cell_source = kin::to_string(a.source);
    p.yaw_rate_clamped = a.yaw_rate_clamped;
    return from_table(std::move(p), std::move(a.prediction));
  } catch (const kin::CktRangeError& e) {
    return invalid_argument("speed", e.what());
  }
}

// What an answer must not have learnt from: a mission, one stored turn (and, for a model, the
// turn's mission: models are trained on whole missions).
struct HeldOut {
  store::TurnsLeftOut left_out;               // what the table must not be built from
  std::vector<std::int64_t> unseen_missions;  // a model trained on any of these is not fair
  std::string text;                           // "mission 3", "turn 12", "mission 3 and turn 12"
};

Result<HeldOut> held_out_of(Context& ctx, const PredictQuery& q) {
  HeldOut h;
  h.left_out.mission_id = q.without_mission_id;
  h.left_out.turn_id = q.without_turn_id;
  store::Store& db = store_of(ctx);
  if (h.left_out.mission_id) {
    if (!db.missions().get(*h.left_out.mission_id))
      return not_found("no mission " + std::to_string(*h.left_out.mission_id));
    h.unseen_missions.push_back(*h.left_out.mission_id);
    h.text = "mission " + std::to_string(*h.left_out.mission_id);
  }
  if (h.left_out.turn_id) {
    const auto row = db.turns().get_row(*h.left_out.turn_id);
    if (!row) return not_found("no turn " + std::to_string(*h.left_out.turn_id));
    if (row->vehicle_id != q.vehicle_id)
      return invalid_argument("without_turn", "turn " + std::to_string(*h.left_out.turn_id) +
                                                  " belongs to vehicle '" + row->vehicle_id +
                                                  "', not '" + q.vehicle_id + "'");
    h.unseen_missions.push_back(row->mission_id);
    h.text += (h.text.empty() ? "" : " and ") + ("turn " + std::to_string(*h.left_out.turn_id));
  }
  return h;
}

// avk without a mission or a turn: a table of the vehicle's other ok turns (the full table holds
// every turn), kept per left-out set until the vehicle's turns change (TableCache::held_out). The
// coarse table answers: a fine one is not worth building for the few queries of one set.
Result<Prediction> from_held_out_table(Context& ctx, Prediction p, const HeldOut& h) {
  const PredictQuery& q = p.query;
  if (q.initial_yaw_rate_dps || q.speed_after_mps)
    return invalid_argument(h.left_out.mission_id ? "without_mission" : "without_turn",
                            "applies to constant-speed turns from a steady course; ask without "
                            "initial_yaw_rate and speed_after");
  const auto held_out_table =
      ctx.tables().held_out(ctx, q.vehicle_id, q.include_harvested, h.left_out);
  if (!held_out_table)
    return not_found("'" + q.vehicle_id + "' has no ok turns outside " + h.text +
                     " to build a table from");
  const kin::Ckt& table = *held_out_table;
  p.table_source = "turns";
  p.table_frame = kin::to_string(table.frame);
  try {
    return from_table(std::move(p), table.query(q.speed_mps, q.dheading_deg));
  } catch (const kin::CktRangeError& e) {
    return table_range_error(table, q, e.what());
  }
}

// The model that answers: the one asked for, else the vehicle's latest; one not trained on the
// held-out missions when there are any.
Result<store::StoredModel> answering_model(Context& ctx, const PredictQuery& q,
                                           const std::vector<std::int64_t>& unseen) {
  store::Store& db = store_of(ctx);
  const auto trained_on = [&](const store::StoredModel& m) -> std::optional<std::int64_t> {
    for (const auto id : unseen)
      if (std::ranges::find(m.training_missions, id) != m.training_missions.end()) return id;
    return std::nullopt;
  };
  if (q.model_id) {
    auto m = db.models().get(*q.model_id);
    if (!m) return not_found("no model " + std::to_string(*q.model_id));
    if (const auto seen = trained_on(*m))
      return invalid_argument("model", "model " + std::to_string(m->id) +
                                           " was trained on mission " + std::to_string(*seen));
    return std::move(*m);
  }
  if (unseen.empty()) {
    auto m = db.models().latest(q.vehicle_id);
    if (!m) return not_found("no model of '" + q.vehicle_id + "' is stored");
    return std::move(*m);
  }
  std::optional<store::StoredModel> best;
  for (auto& m : db.models().list(q.vehicle_id))
    if (!trained_on(m) && (!best || m.id > best->id)) best = std::move(m);
  if (!best) {
    std::string missions;
    for (const auto id : unseen)
      missions += (missions.empty() ? "" : " or ") + std::to_string(id);
    return not_found("every stored model of '" + q.vehicle_id + "' was trained on mission " +
                     missions);
  }
  return std::move(*best);
}

// The trajectory through the water carried by a current (in its frame) as the vehicle's speed
// loop flies it, point for point: a loop holding the speed over ground flies each segment at the
// speed through the water that makes its still-water speed good over ground, so the segment is
// re-timed and carried for that time (kinematics::retimed_over_ground); a loop holding the speed
// through the water keeps the timing and is carried by c·t. Times from the table's recorded
// timing, else constant speed.
kin::Polyline carried_by_current(const kin::Polyline& trajectory,
                                 const std::optional<kin::TurnTiming>& timing, double speed_mps,
                                 kin::Point current_mps, bool speed_over_ground) {
  if (!speed_over_ground)
    return kin::drifted_trajectory(trajectory, timing, speed_mps, current_mps);
  kin::Polyline out;
  out.reserve(trajectory.size());
  const kin::TimedPath water = kin::timed_maneuver(0.0, speed_mps, trajectory, timing).path;
  for (const kin::TimedPoint& p : kin::retimed_over_ground(water, current_mps))
    out.push_back({p.x_m, p.y_m});
  return out;
}

Result<Prediction> finish(Prediction p, const std::optional<kin::Corridor>& corridor = {},
                          const std::optional<kin::TurnTiming>& timing = {}) {
  if (p.current) {
    // The current is applied in the normalised frame, before placing, so a pose turns it with
    // the trajectory; the normalised frame's north is the start heading.
    const double heading = p.query.pose ? p.query.pose->heading_deg : 0.0;
    p.trajectory = carried_by_current(
        p.trajectory, timing, p.query.speed_mps,
        kin::current_in_normalized_frame(*p.current, heading, kin::TurnSide::right),
        p.motion.speed_over_ground);
  }
  if (p.query.pose)
    p.trajectory = kin::place_normalized(p.trajectory, *p.query.pose, kin::TurnSide::right);
  // The band is built about the trajectory as it is answered, so it is in the same frame.
  if (corridor && corridor->n_turns >= 2)
    p.corridor = kin::corridor_band(p.trajectory, *corridor, p.query.corridor_share);
  return Result<Prediction>(std::move(p));
}

Result<Prediction> from_table(Prediction p, kin::TurnPrediction t) {
  p.trajectory = std::move(t.trajectory);
  p.advance_m = t.advance_m;
  p.transfer_m = t.transfer_m;
  p.exact_cell = t.exact_cell;
  p.extrapolated = t.extrapolated;
  p.short_of_goal = t.short_of_goal;
  return finish(std::move(p), t.corridor, t.timing);
}

// The speed response a re-timed answer uses: the vehicle's measured one, else its model's.
struct ResponseChoice {
  kin::SpeedResponse response;
  std::string name;
};

std::optional<ResponseChoice> speed_response_for(Context& ctx, const VehicleTable& t,
                                                 const std::string& vehicle_id) {
  if (t.measured_speed_response) return ResponseChoice{*t.measured_speed_response, "measured"};
  const auto m = store_of(ctx).models().latest(vehicle_id);
  if (!m) return std::nullopt;
  if (auto r = kin::speed_response_of_model(m->model)) return ResponseChoice{*r, "model"};
  return std::nullopt;
}

// avk with a speed change: the measured cells of the pair, else the constant-speed turn at u0
// re-timed.
Result<Prediction> predict_speed_change(Context& ctx, const VehicleTable& t, Prediction p) {
  const PredictQuery& q = p.query;
  const double u0 = q.speed_mps, u1 = *q.speed_after_mps;
  if (t.speed_changes) {
    if (auto m = t.speed_changes->query(u0, u1, q.dheading_deg)) {
      p.speed_change_source = SpeedChangeSource::measured;
      return from_table(std::move(p), std::move(*m));
    }
  }
  if (!t.fine) return invalid_argument("speed", "the table holds no turn to predict from");
  const auto response = speed_response_for(ctx, t, q.vehicle_id);
  if (!response)
    return invalid_argument("speed_after",
                            "no speed response to re-time a turn with: '" + q.vehicle_id +
                                "' has no stored speed-change turns and no model with a speed "
                                "model");
  kin::TurnPrediction base;
  try {
    base = t.fine->query(u0, std::abs(q.dheading_deg));
  } catch (const kin::CktRangeError& e) {
    return table_range_error(*t.table, q, e.what());
  }
  const kin::RetimedTurn r = kin::retime_turn(base, u0, u1, response->response);
  p.speed_change_source = SpeedChangeSource::retimed;
  p.speed_response = response->name;
  p.trajectory = q.dheading_deg < 0.0 ? kin::reflect_x(r.trajectory) : r.trajectory;
  p.advance_m = r.advance_m;
  p.transfer_m = r.transfer_m;
  p.exact_cell = false;
  p.extrapolated = base.extrapolated;
  p.short_of_goal = base.short_of_goal;
  return finish(std::move(p));
}

}  // namespace

Result<Prediction> predict_with_table(const kin::Ckt& table, const PredictQuery& query) {
  if (auto problems = turn_problems(query); !problems.empty())
    return turn_error(std::move(problems), &table, query.speed_mps);
  if (auto e = check(query)) return *e;
  const PredictQuery q = without_null_change(query);
  if (q.speed_after_mps)
    return invalid_argument("speed_after",
                            "a CKT file holds constant-speed turns only; ask the station, which "
                            "has the vehicle's speed-change turns and speed response");
  if (q.live_current)
    return invalid_argument("current", "a table file has no live estimate; give the current");
  if (q.current) {
    if (auto e = check_current(*q.current, "current")) return *e;
  }
  Prediction p;
  p.query = q;
  p.table_frame = kin::to_string(table.frame);
  p.current = q.current;
  if (q.current) {
    p.current_source = "query";
    p.frame = "ground";
  }
  // A table file knows nothing of the vehicle's speed loop: the asked reference, else the default.
  if (q.speed_over_ground) {
    p.motion.speed_over_ground = *q.speed_over_ground;
    p.motion.speed_reference_source = "query";
  }
  try {
    return from_table(std::move(p), table.query(q.speed_mps, q.dheading_deg));
  } catch (const kin::CktRangeError& e) {
    return table_range_error(table, q, e.what());
  }
}

Result<Prediction> predict(Context& ctx, const PredictQuery& query) {
  if (auto problems = turn_problems(query); !problems.empty()) {
    std::shared_ptr<const kin::Ckt> table;
    if (query.method == PredictionMethod::avk) {
      if (auto t = vehicle_table(ctx, query.vehicle_id, query.include_harvested)) table = t->table;
    }
    return turn_error(std::move(problems), table.get(), query.speed_mps);
  }
  if (auto e = check(query)) return *e;
  const PredictQuery q = without_null_change(query);
  Prediction p;
  p.query = q;
  auto current =
      query_current(ctx, q.vehicle_id, q.current, q.live_current, "current", q.no_current);
  if (!current) return current.error();
  p.current = current->current;
  p.current_source = current->source;
  p.frame = current->frame;
  p.current_covariance = current->covariance;
  p.motion = answer_motion(ctx, q.vehicle_id, q.speed_over_ground);
  const auto held = held_out_of(ctx, q);
  if (!held) return held.error();
  const HeldOut& held_out = *held;
  switch (q.method) {
    case PredictionMethod::avk: {
      if (held_out.left_out.turn_id || held_out.left_out.mission_id)
        return from_held_out_table(ctx, std::move(p), held_out);
      if (q.initial_yaw_rate_dps) return from_yaw_rate_table(ctx, std::move(p));
      auto t = vehicle_table(ctx, q.vehicle_id, q.include_harvested);
      if (!t) return t.error();
      p.table_source = to_string(t->source);
      p.table_frame = kin::to_string(t->table->frame);
      p.snapshot_id = t->snapshot_id;
      if (q.speed_after_mps) return predict_speed_change(ctx, *t, std::move(p));
      if (!t->fine) return invalid_argument("speed", "the table holds no turn to predict from");
      try {
        // The fine table: the answer guidance gets in its hot path, so every front end gets it.
        return from_table(std::move(p), t->fine->query(q.speed_mps, q.dheading_deg));
      } catch (const kin::CktRangeError& e) {
        return table_range_error(*t->table, q, e.what());
      }
    }
    case PredictionMethod::model: {
      const auto m = answering_model(ctx, q, held_out.unseen_missions);
      if (!m) return m.error();
      if ((q.use_speed_model || q.speed_after_mps) && !m->model.speed)
        return invalid_argument(q.speed_after_mps ? "speed_after" : "speed_model",
                                "model " + std::to_string(m->id) + " has no speed model");
      p.model_id = m->id;
      // A speed change is flown with the speed model following the stepped command.
      if (q.speed_after_mps) p.speed_change_source = SpeedChangeSource::model;
      const double rate =
          q.initial_yaw_rate_dps ? into_turn_dps(*q.initial_yaw_rate_dps, q.dheading_deg) : 0.0;
      try {
        p.trajectory = kin::predict_normalized_turn(
            m->model, q.speed_mps, std::abs(q.dheading_deg), q.completion_threshold_deg, 0.0, 400,
            q.use_speed_model || q.speed_after_mps.has_value(), rate, q.speed_after_mps);
      } catch (const std::invalid_argument& e) {
        return invalid_argument("initial_yaw_rate", e.what());
      }
      if (q.dheading_deg < 0.0) p.trajectory = kin::reflect_x(std::move(p.trajectory));
      return finish(std::move(p));
    }
    case PredictionMethod::instantaneous:
      p.trajectory = instantaneous_turn_ray(q.speed_mps, q.dheading_deg);
      return finish(std::move(p));
  }
  return internal_error("unknown prediction method");
}

}  // namespace avk::app
