#include "app/vehicle_motion.hpp"

#include <algorithm>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/store_access.hpp"
#include "app/vehicles.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

LegMotion leg_motion(const std::vector<kin::SteadyLeg>& legs,
                     const std::optional<kin::CurrentEstimate>& current) {
  LegMotion out;
  if (current) out.speed_reference = kin::identify_speed_reference(legs, *current);
  const kin::SpeedReference ref = out.speed_reference && out.speed_reference->identified
                                      ? *out.speed_reference->identified
                                      : kDefaultSpeedReference;
  std::optional<kin::WaterCurrent> c;
  if (current && current_is_significant(*current)) c = water_current(*current);
  out.drift_scatter = kin::drift_scatter_of(legs, c, ref);
  return out;
}

Result<VehicleMotion> vehicle_motion(Context& ctx, const std::string& vehicle_id,
                                     std::span<const std::int64_t> missions) {
  store::Store& db = store_of(ctx);
  // The station's own vehicle counts before it has stored anything.
  if (auto known = get_vehicle(ctx, vehicle_id); !known) return known.error();
  VehicleMotion out;
  out.vehicle_id = vehicle_id;
  std::vector<kin::DriftScatter> scatters;
  std::optional<store::StoredCurrent> undetermined;  // the newest evaluated, undetermined
  // Oldest first: whatever comes later replaces what came before.
  for (const store::StoredCurrent& c : db.currents().for_vehicle(vehicle_id)) {
    if (!missions.empty() &&
        std::find(missions.begin(), missions.end(), c.mission_id) == missions.end())
      continue;
    if (current_is_significant(c.estimate)) out.current = view_of(c);
    if (c.drift_scatter && c.drift_scatter->legs > 0) scatters.push_back(*c.drift_scatter);
    if (!c.speed_reference) continue;
    MotionSpeedReference& r = out.speed_reference;
    if (!c.speed_reference->identified) {
      ++r.missions_undetermined;
      undetermined = c;
      continue;
    }
    const kin::SpeedReference identified = *c.speed_reference->identified;
    ++(identified == kin::SpeedReference::over_ground ? r.missions_over_ground
                                                      : r.missions_through_water);
    r.value = identified;
    r.source = "identified";
    r.mission_id = c.mission_id;
    r.evidence = c.speed_reference;
  }
  if (out.speed_reference.source == "default" && undetermined) {
    out.speed_reference.mission_id = undetermined->mission_id;
    out.speed_reference.evidence = undetermined->speed_reference;
  }
  if (const auto p = kin::pooled(scatters)) {
    out.drift_scatter.scatter = *p;
    out.drift_scatter.source = "measured";
    out.drift_scatter.missions = scatters.size();
  }
  return out;
}

}  // namespace avk::app
