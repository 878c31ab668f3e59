#pragma once
// Missions as documents: the listing, the report with its cells and running turn, the event log
// and the track.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/missions.hpp"

namespace avk::server {

nlohmann::json mission_json(const app::MissionSummary& m);
nlohmann::json cells_json(const std::vector<app::CellReport>& cells);
// The mission report: the mission, its status (live or stored), cells, turn totals, ConditionSet
// statistics; with the mission document when with_config.
nlohmann::json report_json(const app::MissionReport& r, bool with_config);
// The turn under way: the report's running_turn and the stream's turn "started" are one shape.
nlohmann::json running_turn_json(const mission::RunningTurn& t);
nlohmann::json event_json(const app::MissionEventView& e);
nlohmann::json track_point_json(const app::TrackPoint& n);
std::string missions_csv(const std::vector<app::MissionSummary>& missions);
// The event log and the track as their JSON pages' items, one row each.
std::string events_csv(const std::vector<app::MissionEventView>& events);
std::string nav_csv(const std::vector<app::TrackPoint>& rows);
std::string report_cells_csv(const app::MissionReport& r);

}  // namespace avk::server
