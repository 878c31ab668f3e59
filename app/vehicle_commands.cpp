#include "app/vehicle_commands.hpp"

#include <chrono>
#include <cmath>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "kinematics/number_text.hpp"

namespace avk::app {

namespace {

constexpr std::chrono::milliseconds kCommandWait{2000};

std::optional<Error> check_coordinate(const std::optional<double>& v, const std::string& field) {
  if (!v) return std::nullopt;
  if (!std::isfinite(*v)) return invalid_argument(field, "must be a finite number of metres");
  if (std::abs(*v) > kMaxCommandCoordinateM)
    return invalid_argument(
        field,
        "must be within " + kinematics::fixed_text(kMaxCommandCoordinateM, 0) + " m of the datum");
  return std::nullopt;
}

// The command the request asks for, or what is wrong with it.
Result<mission::VehicleCommand> command_of(const VehicleCommandRequest& r, double max_speed_mps) {
  using mission::VehicleCommandKind;
  mission::VehicleCommand c;
  c.kind = r.kind;
  if (r.kind == VehicleCommandKind::stop) return c;  // nothing else applies
  if (auto e = check_coordinate(r.x_m, "x_m")) return *e;
  if (auto e = check_coordinate(r.y_m, "y_m")) return *e;
  if (r.x_m.has_value() != r.y_m.has_value())
    return invalid_argument(r.x_m ? "y_m" : "x_m", "give x_m and y_m together");
  if (r.x_m) c.point = kinematics::Point{*r.x_m, *r.y_m};
  if (r.kind == VehicleCommandKind::go_to && !c.point)
    return invalid_argument("x_m", "go-to needs the point: x_m and y_m");
  if (r.radius_m) {
    if (!std::isfinite(*r.radius_m) || *r.radius_m <= 0.0 || *r.radius_m > mission::kMaxHoldRadiusM)
      return invalid_argument("radius_m", "must be more than 0 and at most " +
                                              kinematics::fixed_text(mission::kMaxHoldRadiusM, 0) +
                                              " m");
    c.radius_m = *r.radius_m;
  }
  if (r.speed_mps) {
    if (!std::isfinite(*r.speed_mps) || *r.speed_mps <= 0.0)
      return invalid_argument("speed_mps", "must be more than 0");
    if (max_speed_mps > 0.0 && *r.speed_mps > max_speed_mps)
      return invalid_argument("speed_mps", "must be at most the vehicle's top speed, " +
                                               kinematics::fixed_text(max_speed_mps, 2) + " m/s");
    c.speed_mps = *r.speed_mps;
  }
  return c;
}

}  // namespace

Result<VehicleStatus> command_vehicle(Context& ctx, const std::string& vehicle_id,
                                      const VehicleCommandRequest& request) {
  VehicleLoop* loop = ctx.vehicle_loop(vehicle_id);
  if (!loop) {
    if (store_of(ctx).vehicles().get(vehicle_id))
      return conflict("vehicle '" + vehicle_id + "' is not connected to this station");
    return not_found("no vehicle '" + vehicle_id + "'");
  }
  auto c = command_of(request, loop->info().max_speed_mps);
  if (!c) return c.error();
  if (c->kind == mission::VehicleCommandKind::return_to && !c->point) {
    c->point = loop->last_return_point();
    if (!c->point)
      return conflict("no mission has run on vehicle '" + vehicle_id +
                      "' since the station started: give the point to return to");
  }
  if (!loop->command_vehicle(*c)) return conflict("the station is stopping");
  loop->wait_for_tick(kCommandWait);
  return get_vehicle(ctx, vehicle_id);
}

}  // namespace avk::app
