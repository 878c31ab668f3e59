#include "app/collision_watch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "app/ais_contacts.hpp"
#include "app/context.hpp"
#include "app/maneuvers.hpp"
#include "app/traffic.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/path_approach.hpp"

namespace avk::app {

namespace {

// The alarm of a pair clears once its predicted CPA opens this far past the standoff.
double clear_margin_m(double standoff_m) {
  return std::max(5.0, 0.25 * standoff_m);
}

// The vehicle's running turn as its AVK prediction with its corridor, on the station clock from
// the turn's start; none when the vehicle has no table for it (then it is watched on its course).
std::optional<WatchedParty> turn_party(Context& ctx, const VehicleSnapshot& s,
                                       const mission::RunningTurn& turn, double until_s) {
  OngoingQuery q;
  q.vehicle_id = s.info.id;
  q.start = {turn.start.x_m, turn.start.y_m, turn.start.heading_deg};
  q.dheading_deg = turn.dheading_deg;
  q.speed_mps = turn.speed_mps;
  q.elapsed_s = std::max(0.0, s.nav->t_s - turn.start.t_s);
  q.measured = kinematics::Point{s.nav->x_m, s.nav->y_m};
  q.horizon_s = std::min(600.0, until_s - turn.start.t_s);
  if (!(q.horizon_s > q.elapsed_s)) return std::nullopt;
  const auto r = evaluate_ongoing(ctx, q);
  if (!r || r->prediction.size() < 2) return std::nullopt;
  WatchedParty p;
  p.id = s.info.id;
  p.name = s.info.id;
  p.vehicle = true;
  p.basis = "turn";
  for (auto pt : r->prediction) {
    pt.t_s += turn.start.t_s;
    p.path.push_back(pt);
  }
  p.half_width_m = r->half_width_m;
  if (!p.half_width_m.empty() && p.half_width_m.size() != p.path.size()) p.half_width_m.clear();
  return p;
}

std::string pair_text(const WatchPair& p) {
  return p.a_name + " and " + p.b_name;
}

}  // namespace

WatchedParty course_party(const std::string& id, const std::string& name, const std::string& basis,
                          double t_s, double x_m, double y_m, double course_deg, double speed_mps,
                          double until_s) {
  WatchedParty p;
  p.id = id;
  p.name = name;
  p.basis = basis;
  const double c = course_deg * std::numbers::pi / 180.0;
  const double dt = std::max(0.0, until_s - t_s);
  p.path = {{t_s, x_m, y_m},
            {t_s + dt, x_m + std::sin(c) * speed_mps * dt, y_m + std::cos(c) * speed_mps * dt}};
  return p;
}

std::vector<WatchPair> watch_pairs(const std::vector<WatchedParty>& parties) {
  std::vector<WatchPair> out;
  for (std::size_t i = 0; i < parties.size(); ++i) {
    for (std::size_t j = i + 1; j < parties.size(); ++j) {
      const WatchedParty* a = &parties[i];
      const WatchedParty* b = &parties[j];
      if (!a->vehicle && !b->vehicle) continue;
      if (!a->vehicle || (b->vehicle && b->id < a->id)) std::swap(a, b);
      if (a->path.empty() || b->path.empty()) continue;
      const double t0 = std::max(a->path.front().t_s, b->path.front().t_s);
      if (t0 > std::min(a->path.back().t_s, b->path.back().t_s)) continue;
      const auto cpa =
          kinematics::closest_approach(a->path, b->path, a->half_width_m, b->half_width_m);
      const auto pa = kinematics::position_at(a->path, t0);
      const auto pb = kinematics::position_at(b->path, t0);
      WatchPair w;
      w.a = a->id;
      w.b = b->id;
      w.a_name = a->name;
      w.b_name = b->name;
      w.a_basis = a->basis;
      w.b_basis = b->basis;
      w.distance_now_m = std::hypot(pa.x_m - pb.x_m, pa.y_m - pb.y_m);
      w.cpa_m = cpa.distance_m;
      w.cpa_t_s = cpa.time_s;
      out.push_back(std::move(w));
    }
  }
  std::sort(out.begin(), out.end(),
            [](const WatchPair& x, const WatchPair& y) { return x.cpa_m < y.cpa_m; });
  return out;
}

CollisionWatch::CollisionWatch(Context& ctx, CollisionWatchOptions options, double realtime_factor)
    : ctx_(ctx),
      options_(options),
      realtime_factor_(realtime_factor > 0.0 ? realtime_factor : 1.0) {
  view_.enabled = true;
  view_.options = options_;
}

CollisionWatch::~CollisionWatch() {
  stop();
}

void CollisionWatch::start() {
  if (thread_.joinable()) return;
  stopping_ = false;
  thread_ = std::thread([this] {
    const auto period = std::chrono::duration<double>(options_.period_s / realtime_factor_);
    std::unique_lock lock(mutex_);
    while (!stopping_) {
      lock.unlock();
      check();
      lock.lock();
      wake_.wait_for(lock, period, [this] { return stopping_; });
    }
  });
}

void CollisionWatch::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::vector<WatchedParty> CollisionWatch::parties(double& now_s) {
  struct Live {
    VehicleLoop* loop;
    VehicleSnapshot snap;
  };
  std::vector<Live> live;
  now_s = -1e300;
  for (VehicleLoop* loop : ctx_.vehicle_loops()) {
    VehicleSnapshot s = loop->snapshot();
    if (!s.nav || s.link == vehicle::LinkState::disconnected) continue;
    now_s = std::max(now_s, s.nav->t_s);
    live.push_back({loop, std::move(s)});
  }
  std::vector<WatchedParty> out;
  if (live.empty()) return out;
  const double until_s = now_s + options_.horizon_s;
  for (const auto& [loop, s] : live) {
    out.push_back(course_party(s.info.id, s.info.id, "course", s.nav->t_s, s.nav->x_m, s.nav->y_m,
                               s.nav->heading_deg, s.nav->speed_mps, until_s));
    out.back().vehicle = true;
  }
  for (const auto& c : traffic(ctx_).contacts) {
    const auto k = to_kinematics_contact(c);
    if (!k) continue;
    const std::string name = c.name.empty() ? "MMSI " + std::to_string(c.mmsi) : c.name;
    out.push_back(course_party("ais:" + std::to_string(c.mmsi), name, "ais", now_s, k->x_m, k->y_m,
                               k->course_deg, k->speed_mps, until_s));
  }
  // A lone vehicle has nobody to meet: its turn is not predicted for nothing.
  if (out.size() < 2) return out;
  for (std::size_t i = 0; i < live.size(); ++i) {
    const auto& [loop, s] = live[i];
    if (!s.mission_id) continue;
    const auto l = loop->live(*s.mission_id);
    if (!l || !l->turn) continue;
    if (auto p = turn_party(ctx_, s, *l->turn, until_s)) out[i] = std::move(*p);
  }
  return out;
}

void CollisionWatch::check() {
  double now_s = 0.0;
  std::vector<WatchedParty> ps = parties(now_s);
  std::vector<WatchPair> pairs = watch_pairs(ps);
  struct Told {
    std::string vehicle;
    mission::EventKind kind;
    std::string message;
  };
  std::vector<Told> told;
  {
    std::lock_guard lock(mutex_);
    std::map<std::pair<std::string, std::string>, bool> still;
    for (auto& p : pairs) {
      const auto key = std::make_pair(p.a, p.b);
      const auto it = raised_.find(key);
      const bool was = it != raised_.end() && it->second;
      using kinematics::fixed_text;
      if (!was && p.cpa_m < options_.standoff_m) {
        p.alarm = true;
        told.push_back({p.a, mission::EventKind::collision_watch,
                        pair_text(p) + " are predicted to pass " + fixed_text(p.cpa_m, 1) +
                            " m apart in " + fixed_text(std::max(0.0, p.cpa_t_s - now_s), 0) +
                            " s (standoff " + fixed_text(options_.standoff_m, 0) + " m; now " +
                            fixed_text(p.distance_now_m, 0) + " m apart)"});
      } else if (was && p.cpa_m > options_.standoff_m + clear_margin_m(options_.standoff_m)) {
        told.push_back(
            {p.a, mission::EventKind::collision_clear,
             pair_text(p) + " are clear: predicted CPA " + fixed_text(p.cpa_m, 1) + " m"});
      } else {
        p.alarm = was;
      }
      still[key] = p.alarm;
    }
    // A pair no longer watched (a vehicle left, a contact aged out) drops its alarm silently:
    // the vehicle_left event or the contact's absence already says why.
    raised_ = std::move(still);
    view_.t_s = now_s;
    view_.pairs = pairs;
    view_.parties = std::move(ps);
  }
  for (const auto& t : told)
    if (VehicleLoop* loop = ctx_.vehicle_loop(t.vehicle)) loop->announce(now_s, t.kind, t.message);
}

CollisionWatchView CollisionWatch::view() const {
  std::lock_guard lock(mutex_);
  return view_;
}

CollisionWatchView collision_watch_view(Context& ctx) {
  if (const CollisionWatch* w = ctx.collision_watch()) return w->view();
  return {};
}

}  // namespace avk::app
