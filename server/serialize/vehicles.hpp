#pragma once
// Vehicles as documents: their status, a real vehicle's frontseat link, and the live stream's nav
// and helm payloads.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/vehicles.hpp"
#include "mission/helm_mode.hpp"
#include "vehicle/m200.hpp"

namespace avk::server {

// A real vehicle's frontseat link: connected, failsafe, battery_v, sentences, bad_lines,
// last_error, pydir_sent, failsafe_stops, disconnects, last_link_error.
nlohmann::json frontseat_json(const vehicle::M200Status& s);
// The helm's mode by name; null when the helm has not reported one.
nlohmann::json helm_mode_json(const std::optional<mission::HelmMode>& m);
// The helm's command while no mission runs: {kind, x_m, y_m, radius_m, speed_mps, distance_m}
// (null fields where they do not apply or are not known yet), or null.
nlohmann::json vehicle_command_json(const std::optional<app::VehicleCommandState>& c);
nlohmann::json vehicle_json(const app::VehicleStatus& v);
nlohmann::json vehicles_json(const std::vector<app::VehicleStatus>& vehicles);  // vehicle_json's
// The vehicles as vehicle_json's scalar fields, the last navigation as nav_t_s, x_m, ... (an
// M200's frontseat block is JSON only).
std::string vehicles_csv(const std::vector<app::VehicleStatus>& vehicles);
// The live stream's nav and helm payloads of one telemetry tick.
nlohmann::json nav_topic_json(const app::VehicleSnapshot& s);
nlohmann::json helm_topic_json(const app::VehicleSnapshot& s);

}  // namespace avk::server
