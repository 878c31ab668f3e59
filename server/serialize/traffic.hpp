#pragma once
// The traffic the station watches (AIS contacts through gpsd), as GET /api/v1/traffic answers.

#include <nlohmann/json.hpp>

#include "app/traffic.hpp"

namespace avk::server {

nlohmann::json ais_contact_json(const app::AisContactView& c);
nlohmann::json traffic_json(const app::TrafficView& t);

}  // namespace avk::server
