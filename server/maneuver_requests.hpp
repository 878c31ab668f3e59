#pragma once
// The maneuver endpoints' requests read into the use cases' queries (app/maneuvers.hpp,
// app/encounters.hpp). A body is read field by field and every problem is named by its JSON
// pointer (/contacts/0/speed_mps); unknown fields are problems too. The command line (`avk
// maneuver`) writes its options as the same document and reads it here, so both front ends accept
// exactly the same questions.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/encounters.hpp"
#include "app/maneuvers.hpp"
#include "app/result.hpp"
#include "kinematics/geometry.hpp"
#include "server/http/router.hpp"

namespace avk::server {

// What a request may ask at most: every candidate is a predicted path per contact, and a
// simulation runs the plant for the whole horizon.
inline constexpr std::size_t kMaxManeuverContacts = 50;
inline constexpr std::size_t kMaxManeuverCandidates = 721;
inline constexpr double kMaxManeuverHorizonS = 600.0;
inline constexpr std::size_t kMaxSimulatedContacts = 16;
inline constexpr double kMaxSimulatedHorizonS = 300.0;
inline constexpr double kDefaultPathStepS = 0.5;

struct ManeuverRequest {
  app::ManeuverQuery query;
  // The paths in the answer keep one point per path_step_s (0: every point); the CPAs are
  // computed on the whole paths.
  double path_step_s = kDefaultPathStepS;
};

// POST /vehicles/{vid}/maneuvers/evaluate. invalid_argument with every problem in Error::fields
// (JSON pointers) and the first one in Error::field.
app::Result<ManeuverRequest> maneuver_request(const nlohmann::json& body,
                                              const std::string& vehicle_id);

struct SimulateRequest {
  app::SimulatedManeuverQuery query;  // setup left at its default: the station fills it in
  kinematics::Point own_position;     // the simulator starts at the origin: the track is shifted
  std::optional<double> standoff_m;   // given: the answer says whether it was violated
  double path_step_s = kDefaultPathStepS;
};

// POST /vehicles/{vid}/maneuvers/simulate. Errors as maneuver_request's.
app::Result<SimulateRequest> simulate_request(const nlohmann::json& body);

// GET /vehicles/{vid}/maneuvers/ongoing?x=&y=&heading=&dheading=&speed=&elapsed=[&mx=&my=]
// [&method=][&model=][&corridor=][&horizon=]. Throws RequestError (400) naming the parameter.
app::OngoingQuery ongoing_query(const ApiRequest& r, const std::string& vehicle_id);

}  // namespace avk::server
