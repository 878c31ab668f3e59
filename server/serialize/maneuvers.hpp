#pragma once
// Maneuvers as documents: candidates scored by CPA against the contacts, a maneuver in progress,
// one flown in the simulator.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/encounters.hpp"
#include "app/maneuvers.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/timed_path.hpp"
#include "server/maneuver_requests.hpp"

namespace avk::server {

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
// POST /vehicles/{vid}/maneuvers/simulate: the flight of the request with the vehicle and the
// setup it was flown with; a vehicle other than the station's simulated one (station_setup
// false) is flown with the default setup named, and the answer says so.
nlohmann::json maneuver_simulation_json(const app::SimulatedManeuver& m,
                                        const SimulateRequest& request,
                                        const std::string& vehicle_id, bool station_setup,
                                        const std::string& default_setup);
// `avk maneuver fly --format json`: the flight with its setup, horizon and settling time.
nlohmann::json maneuver_flight_json(const app::SimulatedManeuver& m,
                                    const SimulateRequest& request);
// [t_s, x_m, y_m] rows at thinned_indices(path, step_s).
std::string timed_path_csv(const kinematics::TimedPath& path, double step_s);

}  // namespace avk::server
