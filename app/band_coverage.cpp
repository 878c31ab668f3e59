#include "app/band_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/maneuvers.hpp"
#include "app/mission_legs.hpp"
#include "app/store_access.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/position_band.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {

// The predicted point and band at t on a path with one covariance per point (linear between).
struct BandAt {
  kin::Point p;
  kin::Covariance2 c;
};
BandAt band_at(const kin::TimedPath& path, const std::vector<kin::Covariance2>& cov, double t) {
  std::size_t i = 1;
  while (i < path.size() && path[i].t_s < t)
    ++i;
  if (i >= path.size()) return {{path.back().x_m, path.back().y_m}, cov.back()};
  const auto& a = path[i - 1];
  const auto& b = path[i];
  const double w = b.t_s > a.t_s ? std::clamp((t - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0) : 1.0;
  const auto& ca = cov[i - 1];
  const auto& cb = cov[i];
  return {{a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m)},
          {ca[0] + w * (cb[0] - ca[0]), ca[1] + w * (cb[1] - ca[1]), ca[2] + w * (cb[2] - ca[2])}};
}

// Sums for ErrorStats.
struct ErrorSums {
  std::size_t n = 0;
  double a = 0, aa = 0, va = 0, c = 0, cc = 0, vc = 0;
  void add(double along, double cross, double var_along, double var_cross) {
    ++n;
    a += along, aa += along * along, va += var_along;
    c += cross, cc += cross * cross, vc += var_cross;
  }
  ErrorStats stats() const {
    ErrorStats s;
    s.n = n;
    if (n == 0) return s;
    const double k = static_cast<double>(n);
    s.along_mean_m = a / k, s.along_rms_m = std::sqrt(aa / k),
    s.along_band_sd_m = std::sqrt(va / k);
    s.cross_mean_m = c / k, s.cross_rms_m = std::sqrt(cc / k),
    s.cross_band_sd_m = std::sqrt(vc / k);
    return s;
  }
};

// The path's direction at t: its motion over a second about t.
kin::Point direction_at(const kin::TimedPath& path, const std::vector<kin::Covariance2>& cov,
                        double t) {
  const kin::Point a = band_at(path, cov, t - 0.5).p, b = band_at(path, cov, t + 0.5).p;
  const double n = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  if (!(n > 1e-9)) return {0.0, 1.0};
  return {(b.x_m - a.x_m) / n, (b.y_m - a.y_m) / n};
}

bool same(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b) return a.has_value() == b.has_value();
  return std::abs(*a - *b) < 1e-9;
}

}  // namespace

Result<BandCoverage> band_coverage(Context& ctx, const BandCoverageQuery& q) {
  if (q.test_missions.empty()) return invalid_argument("test_missions", "name a test mission");
  if (!(q.share > 0.0 && q.share < 1.0))
    return invalid_argument("share", "must be a share within (0, 1)");
  if (!(q.after_turn_s >= 0.0 && q.after_turn_s <= 600.0))
    return invalid_argument("after_turn_s", "must be within [0, 600] s");
  store::Store& db = store_of(ctx);
  for (const auto id : q.test_missions)
    if (!db.missions().get(id)) return not_found("no mission " + std::to_string(id));
  std::vector<std::int64_t> table_missions = q.table_missions;
  if (table_missions.empty())
    for (const auto& m : db.missions().list())
      if (m.vehicle_id == q.vehicle_id) table_missions.push_back(m.id);
  // The table never holds a turn it is judged on.
  std::erase_if(table_missions, [&](std::int64_t id) {
    return std::find(q.test_missions.begin(), q.test_missions.end(), id) != q.test_missions.end();
  });
  const auto turns = db.turns().load_normalized(table_missions, q.vehicle_id, false,
                                                store::TurnFrameChoice::water_where_known);
  if (turns.empty()) return not_found("no ok turns of '" + q.vehicle_id + "' to build from");
  const kin::Ckt table = kin::Ckt::build(turns);
  if (!table.speed_range_mps()) return not_found("the table holds no turn to predict from");
  const kin::MaterializedCkt fine(table);

  BandCoverage out;
  out.table_missions = table_missions;
  out.test_missions = q.test_missions;
  out.share = q.share;
  // The speed reference and scatter as the table's missions measured them, not the tests'.
  const AnswerMotion motion = answer_motion(ctx, q.vehicle_id, q.speed_over_ground, table_missions);
  out.speed_over_ground = motion.speed_over_ground;
  out.scatter_along_mps = motion.scatter.along_mps;
  out.scatter_cross_mps = motion.scatter.cross_mps;
  const double k2 = std::pow(kin::band_radius_factor(q.share), 2);
  std::map<long, SpeedCoverage> by_speed;  // keyed by cm/s
  ErrorSums during_sums, after_sums;

  for (const auto mission_id : q.test_missions) {
    // The current as the station knew it for this mission (its own estimate), when told apart
    // from still water; its uncertainty either way.
    std::optional<kin::WaterCurrent> current;
    std::optional<std::array<double, 3>> covariance;
    if (const auto c = db.currents().for_mission(mission_id)) {
      covariance = c->estimate.covariance;
      if (current_is_significant(c->estimate)) current = water_current(c->estimate);
    }
    const kin::BandSources sources = band_sources(motion, covariance);
    const std::vector<store::NavRow> nav = db.navigation().for_mission(mission_id);
    std::vector<store::TurnRow> rows;
    for_each_mission_turn(db, mission_id, kin::TurnStatus::ok,
                          [&](const store::TurnRow& r) { rows.push_back(r); });
    for (const auto& row : rows) {
      const auto stored = db.turns().get(row.id);
      if (!stored || stored->raw.samples().size() < 2) continue;
      const kin::TurnSequence& raw = stored->raw;
      const kin::TurnMeta& meta = raw.meta();
      const double u = meta.commanded_speed_mps, d = meta.goal_dheading_deg;
      kin::TurnPrediction t;
      try {
        t = fine.query(u, d);
      } catch (const kin::CktRangeError&) {
        continue;  // a speed the table does not hold
      }
      const double t0 = raw.samples().front().t_s;
      // The observed positions: the turn, then the steady run after it while the command holds.
      std::vector<std::pair<kin::TimedPoint, bool>> seen;  // (t from command, x, y), after turn
      for (const auto& s : raw.samples())
        seen.push_back({{s.t_s - t0, s.x_m, s.y_m}, false});
      const double end = raw.samples().back().t_s;
      // The run after the turn lasts while the turn's own command holds: the command of the last
      // sample within the turn, so a new command given as the turn ends (containment turning back,
      // the next condition set) ends the run at once.
      std::optional<double> held_heading, held_speed;
      bool known = false;
      for (const auto& n : nav) {
        if (n.t_s <= end) {
          held_heading = n.desired_heading_deg, held_speed = n.desired_speed_mps;
          known = true;
          continue;
        }
        if (!known || n.t_s > end + q.after_turn_s) break;
        if (!same(n.desired_heading_deg, held_heading) || !same(n.desired_speed_mps, held_speed))
          break;
        seen.push_back({{n.t_s - t0, n.x_m, n.y_m}, true});
      }
      const double horizon = std::max(1.0, seen.back().first.t_s + 1.0);
      const kin::PredictedManeuver normalized = table_maneuver(t, u, d, q.share);
      const kin::Pose start{raw.samples().front().x_m, raw.samples().front().y_m,
                            meta.initial_heading_deg};
      const kin::PredictedManeuver m =
          kin::placed_over_ground(normalized, start, current, motion.speed_over_ground, horizon);
      const std::vector<kin::Covariance2> cov =
          kin::position_band(m.path, m.along_sd_m, m.cross_sd_m, m.turn_points, sources);
      SpeedCoverage& sc = by_speed[std::lround(u * 100.0)];
      sc.speed_mps = u;
      ++sc.turns;
      ++out.turns;
      for (const auto& [p, after] : seen) {
        const BandAt b = band_at(m.path, cov, p.t_s);
        const kin::Point e{p.x_m - b.p.x_m, p.y_m - b.p.y_m};
        const bool in = kin::mahalanobis2(b.c, e) <= k2;
        const kin::Point u = direction_at(m.path, cov, p.t_s);
        const kin::Point n{u.y_m, -u.x_m};
        (after ? after_sums : during_sums)
            .add(e.x_m * u.x_m + e.y_m * u.y_m, e.x_m * n.x_m + e.y_m * n.y_m,
                 kin::variance_along(b.c, u), kin::variance_along(b.c, n));
        kin::Coverage one{in ? 1u : 0u, 1u};
        (after ? sc.after_turn : sc.during_turn) += one;
        sc.all += one;
        (after ? out.after_turn : out.during_turn) += one;
        out.all += one;
      }
    }
  }
  if (out.turns == 0) return not_found("the test missions hold no ok turn the table answers");
  for (auto& [key, sc] : by_speed)
    out.by_speed.push_back(sc);
  out.errors_during_turn = during_sums.stats();
  out.errors_after_turn = after_sums.stats();
  return out;
}

}  // namespace avk::app
