#include "app/vehicles.hpp"

#include <algorithm>

#include "app/context.hpp"
#include "app/store_access.hpp"

namespace avk::app {

namespace {

VehicleStatus stored_vehicle(Context& ctx, const std::string& id) {
  VehicleStatus s;
  if (auto v = store_of(ctx).vehicles().get(id)) s.info = std::move(*v);
  s.info.id = id;
  return s;
}

}  // namespace

std::vector<VehicleStatus> list_vehicles(Context& ctx) {
  std::vector<VehicleStatus> out;
  for (VehicleLoop* loop : ctx.vehicle_loops()) {
    VehicleSnapshot snap = loop->snapshot();
    out.push_back({snap.info, std::move(snap)});
  }
  for (const auto& m : store_of(ctx).missions().list()) {
    const bool listed = std::any_of(
        out.begin(), out.end(), [&](const VehicleStatus& v) { return v.info.id == m.vehicle_id; });
    if (!listed) out.push_back(stored_vehicle(ctx, m.vehicle_id));
  }
  return out;
}

Result<VehicleStatus> get_vehicle(Context& ctx, const std::string& vehicle_id) {
  if (VehicleLoop* loop = ctx.vehicle_loop(vehicle_id)) {
    VehicleSnapshot snap = loop->snapshot();
    return VehicleStatus{snap.info, std::move(snap)};
  }
  if (store_of(ctx).vehicles().get(vehicle_id)) return stored_vehicle(ctx, vehicle_id);
  return not_found("no vehicle '" + vehicle_id + "'");
}

}  // namespace avk::app
