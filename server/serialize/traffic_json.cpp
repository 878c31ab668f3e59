#include "server/serialize/traffic.hpp"

#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;

json ais_contact_json(const app::AisContactView& c) {
  return {{"mmsi", c.mmsi},
          {"name", c.name},
          {"callsign", c.callsign},
          {"ship_type", c.ship_type ? json(*c.ship_type) : json()},
          {"lat_deg", c.lat_deg},
          {"lon_deg", c.lon_deg},
          {"x_m", c.x_m},
          {"y_m", c.y_m},
          {"course_deg", optional_json(c.course_deg)},
          {"speed_mps", optional_json(c.speed_mps)},
          {"heading_deg", optional_json(c.heading_deg)},
          {"position_accuracy_high", c.position_accuracy_high},
          {"age_s", c.age_s}};
}

json traffic_json(const app::TrafficView& t) {
  json contacts = json::array();
  for (const auto& c : t.contacts)
    contacts.push_back(ais_contact_json(c));
  return {{"watching", t.watching},
          {"source", t.watching ? json(t.source) : json()},
          {"link_up", t.link_up},
          {"contacts", std::move(contacts)}};
}

}  // namespace avk::server
