#include "server/serialize/vehicles.hpp"

#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;

json frontseat_json(const vehicle::M200Status& s) {
  const auto& c = s.counters;
  return {{"connected", s.connected},
          {"failsafe", vehicle::to_string(s.failsafe)},
          {"battery_v", s.battery ? json(s.battery->stack_v) : json()},
          {"sentences", c.sentences},
          {"bad_lines", c.errors},
          {"last_error", c.last_error},
          {"pydir_sent", c.pydir_sent},
          {"failsafe_stops", c.failsafe_stops},
          {"disconnects", c.disconnects},
          {"last_link_error", s.last_link_error}};
}

json helm_mode_json(const std::optional<mission::HelmMode>& m) {
  return m ? json(mission::to_string(*m)) : json();
}

json vehicle_command_json(const std::optional<app::VehicleCommandState>& c) {
  if (!c) return nullptr;
  const mission::VehicleCommand& k = c->command;
  return {{"kind", mission::to_string(k.kind)},
          {"x_m", k.point ? json(k.point->x_m) : json()},
          {"y_m", k.point ? json(k.point->y_m) : json()},
          {"radius_m", k.kind == mission::VehicleCommandKind::stop ? json() : json(k.radius_m)},
          {"speed_mps", optional_json(k.speed_mps)},
          {"distance_m", optional_json(c->distance_m)}};
}

json vehicle_json(const app::VehicleStatus& v) {
  json j = {{"id", v.info.id},
            {"kind", v.info.kind.empty() ? json() : json(v.info.kind)},
            {"max_speed_mps", v.info.max_speed_mps > 0.0 ? json(v.info.max_speed_mps) : json()}};
  if (!v.live) {
    j["link"] = vehicle::to_string(vehicle::LinkState::disconnected);
    j["nav"] = nullptr;
    return j;
  }
  const app::VehicleSnapshot& s = *v.live;
  j["link"] = vehicle::to_string(s.link);
  j["helm_mode"] = helm_mode_json(s.helm_mode);
  j["desired_heading_deg"] = optional_json(s.desired_heading_deg);
  j["desired_speed_mps"] = optional_json(s.desired_speed_mps);
  j["mission_id"] = optional_json(s.mission_id);
  j["command"] = vehicle_command_json(s.command);
  j["t_s"] = s.t_s;
  j["nav"] = s.nav ? json{{"t_s", s.nav->t_s},
                          {"x_m", s.nav->x_m},
                          {"y_m", s.nav->y_m},
                          {"heading_deg", s.nav->heading_deg},
                          {"speed_mps", s.nav->speed_mps}}
                   : json();
  // A real vehicle's link health: what an operator checks before trusting the turns.
  if (s.frontseat) j["frontseat"] = frontseat_json(*s.frontseat);
  return j;
}

json nav_topic_json(const app::VehicleSnapshot& s) {
  json j = {{"vehicle_id", s.info.id}, {"link", vehicle::to_string(s.link)}};
  if (s.nav) {
    j["t_s"] = s.nav->t_s;
    j["x_m"] = s.nav->x_m;
    j["y_m"] = s.nav->y_m;
    j["heading_deg"] = s.nav->heading_deg;
    j["speed_mps"] = s.nav->speed_mps;
  }
  // A real vehicle's battery and link health ride along with its navigation, so an operator
  // sees a sagging pack or a noisy link live.
  if (s.frontseat) j["frontseat"] = frontseat_json(*s.frontseat);
  return j;
}

json helm_topic_json(const app::VehicleSnapshot& s) {
  return {{"vehicle_id", s.info.id},
          {"mode", helm_mode_json(s.helm_mode)},
          {"desired_heading_deg", optional_json(s.desired_heading_deg)},
          {"desired_speed_mps", optional_json(s.desired_speed_mps)},
          {"mission_id", optional_json(s.mission_id)},
          {"command", vehicle_command_json(s.command)}};
}

json vehicles_json(const std::vector<app::VehicleStatus>& vehicles) {
  json out = json::array();
  for (const auto& v : vehicles)
    out.push_back(vehicle_json(v));
  return out;
}

}  // namespace avk::server
