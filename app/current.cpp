#include "app/current.hpp"

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/water_frame.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

void for_each_mission_turn(store::Store& db, std::int64_t mission_id,
                           std::optional<kin::TurnStatus> status,
                           const std::function<void(const store::TurnRow&)>& fn) {
  store::TurnFilter f;
  f.mission_id = mission_id;
  f.status = status;
  f.limit = 1000;
  for (;;) {
    const auto page = db.list_turns(f);
    for (const auto& row : page)
      fn(row);
    if (page.size() < static_cast<std::size_t>(f.limit)) break;
    f.after_id = page.back().id;
  }
}

std::vector<kin::SteadyLeg> steady_legs_before(const std::vector<double>& turn_starts_s,
                                               const std::vector<store::NavRow>& nav,
                                               double leg_s) {
  std::vector<kin::SteadyLeg> legs;
  for (const double start : turn_starts_s) {
    // The last row before the command: what was in force while conditions were set.
    const auto end = std::lower_bound(nav.begin(), nav.end(), start,
                                      [](const store::NavRow& r, double t) { return r.t_s < t; });
    if (end == nav.begin()) continue;
    const store::NavRow& last = *(end - 1);
    if (!last.desired_heading_deg || !last.desired_speed_mps || !(*last.desired_speed_mps > 0.0))
      continue;
    kin::SteadyLeg leg;
    double s = 0.0, c = 0.0;
    for (auto it = end; it != nav.begin();) {
      const store::NavRow& r = *--it;
      if (r.t_s < start - leg_s) break;
      // The same guidance as at the command; anything else is the leg's beginning.
      if (!r.desired_heading_deg || !r.desired_speed_mps ||
          std::abs(kin::angle180_deg(*r.desired_heading_deg - *last.desired_heading_deg)) > 1e-6 ||
          std::abs(*r.desired_speed_mps - *last.desired_speed_mps) > 1e-9)
        break;
      leg.t_s.push_back(r.t_s);
      leg.x_m.push_back(r.x_m);
      leg.y_m.push_back(r.y_m);
      s += std::sin(kin::deg_to_rad(r.heading_deg));
      c += std::cos(kin::deg_to_rad(r.heading_deg));
    }
    if (leg.t_s.size() < 3 || leg.t_s.front() - leg.t_s.back() < kMinSteadyLegS) continue;
    std::reverse(leg.t_s.begin(), leg.t_s.end());
    std::reverse(leg.x_m.begin(), leg.x_m.end());
    std::reverse(leg.y_m.begin(), leg.y_m.end());
    leg.heading_deg = kin::heading_of_deg(s, c);
    leg.water_speed_mps = *last.desired_speed_mps;
    legs.push_back(std::move(leg));
  }
  return legs;
}

Result<MissionCurrent> estimate_mission_current(Context& ctx, std::int64_t mission_id,
                                                double leg_s) {
  store::Store& db = ctx.db();
  if (!db.get_mission(mission_id)) return not_found("no mission " + std::to_string(mission_id));
  MissionCurrent out;
  out.mission_id = mission_id;
  std::vector<double> starts;
  for_each_mission_turn(db, mission_id, std::nullopt,
                        [&](const store::TurnRow& t) { starts.push_back(t.start_time_s); });
  out.turns = starts.size();
  std::sort(starts.begin(), starts.end());
  const auto legs = steady_legs_before(starts, db.nav_for_mission(mission_id), leg_s);
  out.legs_used = legs.size();
  out.result = kin::estimate_current(legs);
  return out;
}

Result<MissionCurrent> estimate_mission_current_from_turns(Context& ctx, std::int64_t mission_id) {
  store::Store& db = ctx.db();
  const auto mission = db.get_mission(mission_id);
  if (!mission) return not_found("no mission " + std::to_string(mission_id));
  store::TurnsLeftOut others;
  others.mission_id = mission_id;
  const auto table_turns = db.load_normalized_turns(
      {}, mission->vehicle_id, false, store::TurnFrameChoice::water_where_known, others);
  if (table_turns.empty())
    return not_found("no other mission of '" + mission->vehicle_id +
                     "' holds turns to predict this one's with");
  const kin::Ckt table = kin::Ckt::build(table_turns);
  MissionCurrent out;
  out.mission_id = mission_id;
  std::vector<kin::TurnResidual> residuals;
  for_each_mission_turn(db, mission_id, kin::TurnStatus::ok, [&](const store::TurnRow& row) {
    ++out.turns;
    const auto stored = db.get_turn(row.id);
    if (!stored || stored->raw.samples().size() < 2) return;
    const kin::TurnSequence& raw = stored->raw;
    const double speed = raw.meta().commanded_speed_mps;
    const double goal = std::abs(raw.meta().goal_dheading_deg);
    kin::TurnPrediction p;
    try {
      p = table.query(speed, goal);
    } catch (const kin::CktRangeError&) {
      return;
    }
    const auto& first = raw.samples().front();
    const double duration = raw.samples().back().t_s - first.t_s;
    if (!(duration > 0.0)) return;
    kin::Polyline trajectory = std::move(p.trajectory);
    if (raw.side() == kin::TurnSide::left) trajectory = kin::reflect_x(std::move(trajectory));
    const kin::PredictedManeuver m = kin::extended_to_horizon(
        kin::timed_maneuver(raw.meta().goal_dheading_deg, speed, trajectory, p.timing), duration);
    const kin::TimedPath predicted =
        kin::placed(m.path, {first.x_m, first.y_m, raw.meta().initial_heading_deg});
    kin::TurnResidual r;
    for (const auto& s : raw.samples()) {
      const double t = s.t_s - first.t_s;
      const kin::Point e = kin::evaluate_ongoing(predicted, {}, t, std::nullopt).expected;
      r.t_s.push_back(t);
      r.residual_m.push_back({s.x_m - e.x_m, s.y_m - e.y_m});
    }
    residuals.push_back(std::move(r));
  });
  out.legs_used = residuals.size();
  out.result = kin::estimate_current_from_turns(residuals);
  return out;
}

bool current_is_significant(const kin::CurrentEstimate& e) {
  return e.speed_mps() >= kMinCurrentMps && e.speed_mps() >= 2.0 * e.speed_sd_mps();
}

kin::WaterCurrent water_current(const kin::CurrentEstimate& e) {
  return {e.east_mps, e.north_mps};
}

std::vector<std::pair<std::int64_t, kin::TurnSequence>> water_frame_turns(
    const std::vector<std::pair<std::int64_t, kin::TurnSequence>>& raw_turns, kin::WaterCurrent c) {
  std::vector<std::pair<std::int64_t, kin::TurnSequence>> out;
  out.reserve(raw_turns.size());
  for (const auto& [id, raw] : raw_turns) {
    if (raw.meta().normalized || raw.meta().removed_current) continue;
    out.emplace_back(id, kin::in_water_frame(raw, c).normalized());
  }
  return out;
}

Result<AppliedCurrent> apply_mission_current(Context& ctx, std::int64_t mission_id, double leg_s) {
  auto est = estimate_mission_current(ctx, mission_id, leg_s);
  if (!est) return est.error();
  AppliedCurrent out;
  out.current = *est;
  if (!est->result.estimate) return out;
  store::Store& db = ctx.db();
  std::vector<std::pair<std::int64_t, kin::TurnSequence>> raw;
  if (current_is_significant(*est->result.estimate)) {
    for_each_mission_turn(db, mission_id, kin::TurnStatus::ok, [&](const store::TurnRow& t) {
      if (auto stored = db.get_turn(t.id)) raw.emplace_back(t.id, std::move(stored->raw));
    });
  }
  const auto water = water_frame_turns(raw, water_current(*est->result.estimate));
  store::StoredCurrent sc;
  sc.mission_id = mission_id;
  sc.t_s = db.mission_clock_end_s(mission_id).value_or(0.0);
  sc.method = "legs";
  sc.estimate = *est->result.estimate;
  sc.revision = db.save_mission_current(sc, water);
  out.stored = sc;
  out.water_turns = water.size();
  return out;
}

std::optional<Error> check_current(const kin::WaterCurrent& c, const std::string& field) {
  if (std::isfinite(c.east_mps) && std::isfinite(c.north_mps) &&
      std::hypot(c.east_mps, c.north_mps) <= kMaxCurrentMps)
    return std::nullopt;
  return invalid_argument(field, "must be finite east and north components (m/s) of at most " +
                                     kin::number_text(kMaxCurrentMps) + " m/s");
}

Result<QueryCurrent> query_current(Context& ctx, const std::string& vehicle_id,
                                   const std::optional<kin::WaterCurrent>& given, bool live,
                                   const std::string& field, bool none) {
  QueryCurrent out;
  if ((given ? 1 : 0) + (live ? 1 : 0) + (none ? 1 : 0) > 1)
    return invalid_argument(field, "one of a current, live or none");
  if (given) {
    if (auto e = check_current(*given, field)) return *e;
    out.current = given;
    out.source = "query";
    out.frame = "ground";
  } else if (live) {
    auto c = vehicle_current(ctx, vehicle_id);
    if (!c) return c.error();
    out.current = water_current(c->estimate);
    out.covariance = c->estimate.covariance;
    out.source = "live";
    out.frame = "ground";
  } else if (none) {
    out.source = "none";
    out.frame = "water";
  } else if (const auto c = ctx.db().latest_vehicle_current(vehicle_id)) {
    out.frame = "ground";
    out.covariance = c->estimate.covariance;
    if (current_is_significant(c->estimate)) {
      out.current = water_current(c->estimate);
      out.source = "live";
    } else {
      out.source = "still_water";
    }
  } else {
    out.source = "unknown";
    out.frame = "water";
  }
  return out;
}

Result<store::StoredCurrent> vehicle_current(Context& ctx, const std::string& vehicle_id) {
  if (auto c = ctx.db().latest_vehicle_current(vehicle_id)) return *c;
  return not_found("no current has been estimated for vehicle '" + vehicle_id + "'");
}

}  // namespace avk::app
