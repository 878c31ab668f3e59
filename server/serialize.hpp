#pragma once
// The station's domain types as documents: JSON for the API, the live stream and the command
// line's --format json, CSV for exports. One place, so that a mission report or a prediction has
// the same field names wherever it is read. docs/api.md describes the documents.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/ckt_tables.hpp"
#include "app/compare.hpp"
#include "app/current.hpp"
#include "app/encounters.hpp"
#include "app/harvest.hpp"
#include "app/maneuvers.hpp"
#include "app/missions.hpp"
#include "app/models.hpp"
#include "app/predict.hpp"
#include "app/vehicle_motion.hpp"
#include "app/vehicles.hpp"
#include "app/yaw_rate_table.hpp"
#include "kinematics/yaw_identification.hpp"
#include "store/store.hpp"
#include "vehicle/m200.hpp"

namespace avk::server {

// --- values --------------------------------------------------------------------------------

// Numbers in CSV and messages: the shortest text that reads back as the same double.
std::string num(double v);
// Fixed decimals, for tables an operator reads.
std::string fixed(double v, int decimals);
// A record id as a path or an option gives it: a positive whole number, nothing else.
std::optional<std::int64_t> record_id(const std::string& text);
nlohmann::json optional_json(const std::optional<double>& v);
nlohmann::json optional_json(const std::optional<std::int64_t>& v);
nlohmann::json mean_sd_json(const std::optional<kinematics::MeanSd>& v);
nlohmann::json points_json(const kinematics::Polyline& line);  // [[x_m, y_m], ...]

// --- vehicles ------------------------------------------------------------------------------

// A real vehicle's frontseat link: connected, failsafe, battery_v, sentences, bad_lines,
// last_error, pydir_sent, failsafe_stops, disconnects, last_link_error.
nlohmann::json frontseat_json(const vehicle::M200Status& s);
nlohmann::json vehicle_json(const app::VehicleStatus& v);
// The vehicles as vehicle_json's scalar fields, the last navigation as nav_t_s, x_m, ... (an
// M200's frontseat block is JSON only).
std::string vehicles_csv(const std::vector<app::VehicleStatus>& vehicles);
// The live stream's nav and helm payloads of one telemetry tick.
nlohmann::json nav_topic_json(const app::VehicleSnapshot& s);
nlohmann::json helm_topic_json(const app::VehicleSnapshot& s);

// --- missions ------------------------------------------------------------------------------

nlohmann::json mission_json(const app::MissionSummary& m);
nlohmann::json cells_json(const std::vector<app::CellReport>& cells);
// The mission report: the mission, its status (live or stored), cells, turn totals, ConditionSet
// statistics; with the mission document when with_config.
nlohmann::json report_json(const app::MissionReport& r, bool with_config);
// The turn under way: the report's running_turn and the stream's turn "started" are one shape.
nlohmann::json running_turn_json(const mission::RunningTurn& t);
nlohmann::json event_json(const store::MissionEvent& e);
nlohmann::json nav_row_json(const store::NavRow& n);
std::string missions_csv(const std::vector<app::MissionSummary>& missions);
// The event log and the track as their JSON pages' items, one row each.
std::string events_csv(const std::vector<store::MissionEvent>& events);
std::string nav_csv(const std::vector<store::NavPageRow>& rows);
std::string report_cells_csv(const app::MissionReport& r);

// --- turns ---------------------------------------------------------------------------------

nlohmann::json turn_row_json(const store::TurnRow& t);
nlohmann::json harvest_report_json(const app::HarvestReport& r);
nlohmann::json turn_json(const store::StoredTurn& t);  // with raw and normalised trajectories
std::string turns_csv(const std::vector<store::TurnRow>& rows);

// --- the CKT, predictions ------------------------------------------------------------------

nlohmann::json ckt_summary_json(const app::VehicleTable& t);
// A cell on the side asked (app::ckt_cell): `side` "port" or "starboard", dheading_deg signed.
nlohmann::json ckt_cell_json(const app::SidedCell& s);
nlohmann::json prediction_json(const app::Prediction& p);
// {east_mps, north_mps, speed_mps, toward_deg, source}; null without a current.
nlohmann::json water_current_json(const std::optional<kinematics::WaterCurrent>& c,
                                  const std::optional<std::string>& source);
nlohmann::json current_estimate_json(const kinematics::CurrentEstimate& e);
// The stream's `current` topic and GET .../current: an estimate with its mission and revision.
nlohmann::json current_json(const std::string& vehicle_id, const store::StoredCurrent& c);
// An estimate from a mission's navigation, with the stored one (null when none).
nlohmann::json mission_current_json(const app::MissionCurrent& c,
                                    const std::optional<store::StoredCurrent>& stored);
// {legs, rms_over_ground_mps, rms_through_water_mps, separation_mps, identified}; identified is
// "over_ground", "through_water" or null (undetermined); null when not evaluated.
nlohmann::json speed_reference_evidence_json(
    const std::optional<kinematics::SpeedReferenceEvidence>& e);
// {along_mps, cross_mps, legs, mean_leg_s}; null when not measured.
nlohmann::json drift_scatter_json(const std::optional<kinematics::DriftScatter>& d);
// GET /vehicles/{vid}/motion and `avk vehicle motion --format json`.
nlohmann::json vehicle_motion_json(const app::VehicleMotion& m);
// The table over initial yaw rate: its coverage per slice, the model's scores where cells were
// measured, and the schema-4 CKT document (`ckt`).
nlohmann::json yaw_rate_table_json(const app::YawRateTable& t);
std::string trajectory_csv(const kinematics::Polyline& line);

// --- maneuvers ------------------------------------------------------------------------------

// The indices of a timed path kept at one point per step_s (0: every point); the first and the
// last are always kept. What the answers draw; their CPAs come from the whole paths.
std::vector<std::size_t> thinned_indices(const kinematics::TimedPath& path, double step_s);
// [[t_s, x_m, y_m], ...] at those indices.
nlohmann::json timed_path_json(const kinematics::TimedPath& path, double step_s = 0.0);
nlohmann::json approach_json(const kinematics::Approach& a);  // {distance_m, time_s}
nlohmann::json contact_json(const kinematics::Contact& c);
// Every candidate with its path, corridor half widths, CPA per contact, and the choice.
nlohmann::json maneuver_evaluation_json(const app::ManeuverEvaluation& e, double path_step_s);
// The same document as maneuver_evaluation_json(e, path_step_s).dump(), byte for byte, written
// one candidate at a time: hundreds of candidates against dozens of contacts make a document of
// megabytes whose tree is several times the text, and only one candidate's is held here.
std::string maneuver_evaluation_text(const app::ManeuverEvaluation& e, double path_step_s);
nlohmann::json ongoing_maneuver_json(const app::OngoingManeuver& o);
// The flown track (shifted by `origin`: the simulator starts at the origin) and the actual CPAs;
// with a standoff, whether it was violated.
nlohmann::json simulated_maneuver_json(const app::SimulatedManeuver& s, kinematics::Point origin,
                                       std::optional<double> standoff_m, double path_step_s);

// --- models, the comparison ----------------------------------------------------------------

// with_coefficients: the full model document; without, the listing's summary.
nlohmann::json model_json(const store::StoredModel& m, bool with_coefficients = true);
// The listing's summary (no coefficients), the speed model as speed_gain, ...
std::string models_csv(const std::vector<store::StoredModel>& models);
nlohmann::json model_headings_json(const app::ModelHeadings& h);
nlohmann::json sweep_json(const std::vector<kinematics::HistorySweepRow>& rows);
std::string sweep_csv(const std::vector<kinematics::HistorySweepRow>& rows);
nlohmann::json comparison_json(const app::Comparison& c);
// The thesis' in-sample table.
std::string comparison_csv(const app::Comparison& c);
// The leave-one-out table: path distance and y(x) MSE of every method, and corridor coverage.
std::string predictive_csv(const app::Comparison& c);

// A value a client sent, for an error message: a scalar shortened, a container by its kind only.
std::string describe_value(const nlohmann::json& v);

}  // namespace avk::server
