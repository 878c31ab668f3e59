#pragma once
// Missions as documents: the listing, the report with its cells and running turn, the event log
// and the track.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/missions.hpp"
#include "mission/mission_observer.hpp"

namespace avk::server {

nlohmann::json mission_json(const app::MissionSummary& m);
nlohmann::json cells_json(const std::vector<app::CellReport>& cells);
// The mission report: the mission, its status (live or stored), cells, turn totals, ConditionSet
// statistics; with the mission document when with_config.
nlohmann::json report_json(const app::MissionReport& r, bool with_config);
// The turn under way: the report's running_turn and the stream's turn "started" are one shape.
nlohmann::json running_turn_json(const mission::RunningTurn& t);
// The live stream's `turn` messages: a turn started (running_turn_json with event "started"), and
// one ended (event "finished", or its status when it did not finish).
nlohmann::json turn_started_json(const mission::RunningTurn& t, std::int64_t mission_id);
nlohmann::json turn_ended_json(const mission::TurnOutcome& t, std::int64_t mission_id);
// The live stream's `mission` message: the mission's state, the helm's mode, its cells.
nlohmann::json mission_progress_json(std::int64_t mission_id, const std::string& state,
                                     mission::HelmMode helm_mode,
                                     const std::vector<app::CellReport>& cells);
nlohmann::json event_json(const app::MissionEventView& e);
nlohmann::json track_point_json(const app::TrackPoint& n);
// The listing: mission_json of each.
nlohmann::json missions_json(const std::vector<app::MissionSummary>& missions);
// A page of a mission's log or of its track: {items, next}.
nlohmann::json events_page_json(const app::Page<app::MissionEventView>& page);
nlohmann::json nav_page_json(const app::Page<app::TrackPoint>& page);
std::string missions_csv(const std::vector<app::MissionSummary>& missions);
// The event log and the track as their JSON pages' items, one row each.
std::string events_csv(const std::vector<app::MissionEventView>& events);
std::string nav_csv(const std::vector<app::TrackPoint>& rows);
std::string report_cells_csv(const app::MissionReport& r);

}  // namespace avk::server
