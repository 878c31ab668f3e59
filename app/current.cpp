#include "app/current.hpp"
#include "app/mission_legs.hpp"

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "app/vehicle_motion.hpp"
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
    const auto page = db.turns().list(f);
    for (const auto& row : page)
      fn(row);
    if (page.size() < static_cast<std::size_t>(f.limit)) break;
    f.after_id = page.back().id;
  }
}

namespace {

using NavIt = std::vector<store::NavRow>::const_iterator;

// The same guidance as at the command; anything else is the leg's beginning.
bool same_guidance(const store::NavRow& r, const store::NavRow& last) {
  return r.desired_heading_deg && r.desired_speed_mps &&
         std::abs(kin::angle180_deg(*r.desired_heading_deg - *last.desired_heading_deg)) <= 1e-6 &&
         std::abs(*r.desired_speed_mps - *last.desired_speed_mps) <= 1e-9;
}

// The rows [first, end) before the command at start_s during which the guidance in force at the
// command held, from since_s at the earliest, and the speed it commanded. None when there was no
// row before the command or its guidance held no heading and speed > 0. The last row before the
// command is what was in force while conditions were set.
struct Held {
  NavIt first, end;
  double speed_mps;
};
std::optional<Held> held_before(const std::vector<store::NavRow>& nav, double start_s,
                                double since_s) {
  const auto end = std::lower_bound(nav.begin(), nav.end(), start_s,
                                    [](const store::NavRow& r, double t) { return r.t_s < t; });
  if (end == nav.begin()) return std::nullopt;
  const store::NavRow& last = *(end - 1);
  if (!last.desired_heading_deg || !last.desired_speed_mps || !(*last.desired_speed_mps > 0.0))
    return std::nullopt;
  auto first = end;
  while (first != nav.begin() && (first - 1)->t_s >= since_s && same_guidance(*(first - 1), last))
    --first;
  return Held{first, end, *last.desired_speed_mps};
}

// Sums of the unit vectors of headings: their circular mean is heading_of_deg(s, c).
struct HeadingSum {
  double s = 0.0, c = 0.0;
  void add(double heading_deg) {
    s += std::sin(kin::deg_to_rad(heading_deg));
    c += std::cos(kin::deg_to_rad(heading_deg));
  }
  void remove(double heading_deg) {
    s -= std::sin(kin::deg_to_rad(heading_deg));
    c -= std::cos(kin::deg_to_rad(heading_deg));
  }
  double mean_deg() const { return kin::heading_of_deg(s, c); }
};

kin::SteadyLeg leg_of(NavIt first, NavIt end, double speed_mps) {
  kin::SteadyLeg leg;
  HeadingSum h;
  for (auto it = first; it != end; ++it) {
    leg.t_s.push_back(it->t_s);
    leg.x_m.push_back(it->x_m);
    leg.y_m.push_back(it->y_m);
    h.add(it->heading_deg);
  }
  leg.heading_deg = h.mean_deg();
  leg.water_speed_mps = speed_mps;
  return leg;
}

}  // namespace

std::vector<kin::SteadyLeg> steady_legs_before(const std::vector<double>& turn_starts_s,
                                               const std::vector<store::NavRow>& nav,
                                               double leg_s) {
  std::vector<kin::SteadyLeg> legs;
  for (const double start : turn_starts_s) {
    const auto held = held_before(nav, start, start - leg_s);
    if (!held) continue;
    const auto [first, end, speed] = *held;
    if (end - first < 3 || (end - 1)->t_s - first->t_s < kMinSteadyLegS) continue;
    legs.push_back(leg_of(first, end, speed));
  }
  return legs;
}

std::vector<kin::SteadyLeg> steady_stretches_before(const std::vector<double>& turn_starts_s,
                                                    const std::vector<store::NavRow>& nav) {
  std::vector<kin::SteadyLeg> legs;
  for (const double start : turn_starts_s) {
    const auto held = held_before(nav, start, start - kMotionLegMaxS);
    if (!held) continue;
    const auto [first, end, speed] = *held;
    // The reference: the means over the last seconds, which the ConditionSet judged steady.
    HeadingSum ref_heading;
    double ref_speed = 0.0;
    std::size_t ref_rows = 0;
    for (auto it = end; it != first && (it - 1)->t_s >= start - kSteadyReferenceS;) {
      --it;
      ref_heading.add(it->heading_deg);
      ref_speed += it->speed_mps;
      ++ref_rows;
    }
    if (ref_rows < 3) continue;
    ref_speed /= static_cast<double>(ref_rows);
    // Back from the command while each row's smoothed heading and speed stay near the reference.
    // The window [lo, hi) holds the rows within half the smoothing time of the row judged.
    auto lo = end, hi = end, kept = end;
    HeadingSum win_heading;
    double win_speed = 0.0;
    for (auto it = end; it != first;) {
      --it;
      while (lo != first && (lo - 1)->t_s >= it->t_s - 0.5 * kSteadySmoothingS) {
        --lo;
        win_heading.add(lo->heading_deg);
        win_speed += lo->speed_mps;
      }
      while (hi != lo && (hi - 1)->t_s > it->t_s + 0.5 * kSteadySmoothingS) {
        --hi;
        win_heading.remove(hi->heading_deg);
        win_speed -= hi->speed_mps;
      }
      const auto n = static_cast<double>(hi - lo);
      if (std::abs(kin::angle180_deg(win_heading.mean_deg() - ref_heading.mean_deg())) >
              kSteadyHeadingTolDeg ||
          std::abs(win_speed / n - ref_speed) > kSteadySpeedTolMps)
        break;
      kept = it;
    }
    if (end - kept < 3 || (end - 1)->t_s - kept->t_s < kMotionLegMinS) continue;
    legs.push_back(leg_of(kept, end, speed));
  }
  return legs;
}

Result<MissionCurrent> estimate_mission_current(Context& ctx, std::int64_t mission_id,
                                                double leg_s) {
  store::Store& db = store_of(ctx);
  if (!db.missions().get(mission_id)) return not_found("no mission " + std::to_string(mission_id));
  MissionCurrent out;
  out.mission_id = mission_id;
  std::vector<double> starts;
  for_each_mission_turn(db, mission_id, std::nullopt,
                        [&](const store::TurnRow& t) { starts.push_back(t.start_time_s); });
  out.turns = starts.size();
  std::sort(starts.begin(), starts.end());
  const auto nav = db.navigation().for_mission(mission_id);
  const auto legs = steady_legs_before(starts, nav, leg_s);
  out.legs_used = legs.size();
  out.result = kin::estimate_current(legs);
  const auto stretches = steady_stretches_before(starts, nav);
  out.motion_legs = stretches.size();
  LegMotion motion = leg_motion(stretches, out.result.estimate);
  out.speed_reference = motion.speed_reference;
  out.drift_scatter = motion.drift_scatter;
  return out;
}

Result<MissionCurrent> estimate_mission_current_from_turns(Context& ctx, std::int64_t mission_id) {
  store::Store& db = store_of(ctx);
  const auto mission = db.missions().get(mission_id);
  if (!mission) return not_found("no mission " + std::to_string(mission_id));
  store::TurnsLeftOut others;
  others.mission_id = mission_id;
  const auto table_turns = db.turns().load_normalized(
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
    const auto stored = db.turns().get(row.id);
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
  store::Store& db = store_of(ctx);
  std::vector<std::pair<std::int64_t, kin::TurnSequence>> raw;
  if (current_is_significant(*est->result.estimate)) {
    for_each_mission_turn(db, mission_id, kin::TurnStatus::ok, [&](const store::TurnRow& t) {
      if (auto stored = db.turns().get(t.id)) raw.emplace_back(t.id, std::move(stored->raw));
    });
  }
  const auto water = water_frame_turns(raw, water_current(*est->result.estimate));
  store::StoredCurrent sc;
  sc.mission_id = mission_id;
  sc.t_s = db.missions().clock_end_s(mission_id).value_or(0.0);
  sc.method = "legs";
  sc.estimate = *est->result.estimate;
  sc.speed_reference = est->speed_reference;
  sc.drift_scatter = est->drift_scatter;
  sc.revision = db.currents().save(sc, water);
  out.stored = view_of(sc);
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
  } else if (const auto c = store_of(ctx).currents().latest_for_vehicle(vehicle_id)) {
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

Result<std::optional<CurrentView>> stored_mission_current(Context& ctx, std::int64_t mission_id) {
  store::Store& db = store_of(ctx);
  if (!db.missions().get(mission_id)) return not_found("no mission " + std::to_string(mission_id));
  std::optional<CurrentView> out;
  if (const auto c = db.currents().for_mission(mission_id)) out = view_of(*c);
  return out;
}

Result<CurrentView> vehicle_current(Context& ctx, const std::string& vehicle_id) {
  if (auto c = store_of(ctx).currents().latest_for_vehicle(vehicle_id)) return view_of(*c);
  return not_found("no current has been estimated for vehicle '" + vehicle_id + "'");
}

}  // namespace avk::app
