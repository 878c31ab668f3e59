#include "app/current.hpp"

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "kinematics/angles.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

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
  store::TurnFilter f;
  f.mission_id = mission_id;
  f.limit = 1000;
  for (;;) {
    const auto page = db.list_turns(f);
    for (const auto& t : page)
      starts.push_back(t.start_time_s);
    if (page.size() < static_cast<std::size_t>(f.limit)) break;
    f.after_id = page.back().id;
  }
  out.turns = starts.size();
  std::sort(starts.begin(), starts.end());
  const auto legs = steady_legs_before(starts, db.nav_for_mission(mission_id), leg_s);
  out.legs_used = legs.size();
  out.result = kin::estimate_current(legs);
  return out;
}

}  // namespace avk::app
