#pragma once
// The encounter test bench (issue 16): the thesis' question "does assuming instantaneous turns
// lead to poor guidance decisions?" answered in the simulator. For each scenario and method the
// maneuver is chosen at t = 0 (evaluate_maneuvers), then flown closed-loop with the same plant,
// controller and disturbances as a mission while the contacts move, and the actual CPA measured.
// Every candidate is flown too, so the bench knows whether a safe maneuver existed.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/maneuvers.hpp"
#include "app/result.hpp"
#include "kinematics/maneuver.hpp"
#include "sim/sim_config.hpp"

namespace avk::app {

class Context;

struct EncounterScenario {
  std::string name;
  double own_heading_deg = 0.0;  // own vehicle starts at the origin, steady
  double own_speed_mps = 1.0;
  std::vector<kinematics::Contact> contacts;  // positions at t = 0
  double standoff_m = 10.0;                   // the scenario's, or the file's
};

struct EncounterFile {
  int schema_version = 1;
  double standoff_m = 10.0;
  double horizon_s = 120.0;
  std::vector<EncounterScenario> scenarios;
};

// Parses and validates a scenario file (docs/encounter-format.md). invalid_argument with every
// problem in Error::fields, each naming its JSON pointer (/scenarios/3/contacts/0/speed_mps).
Result<EncounterFile> parse_encounter_file(std::string_view json_text);

// One maneuver flown closed-loop: own vehicle steady at the origin on its heading and speed at
// t = 0, commanded heading + dheading and the speed, flown for horizon_s; contacts on straight
// lines. The track is the vehicle's true position (not the noisy navigation).
struct SimulatedManeuverQuery {
  sim::SimSetup setup;  // vehicle kind, disturbances, controller, rates
  std::uint64_t seed = 1;
  double own_heading_deg = 0.0;
  double own_speed_mps = 1.0;
  double dheading_deg = 0.0;
  std::optional<double> speed_mps;  // none: the own speed
  std::vector<kinematics::Contact> contacts;
  double horizon_s = 120.0;
};

struct SimulatedManeuver {
  kinematics::TimedPath track;            // world frame, t = 0 at the command
  std::vector<kinematics::Approach> cpa;  // actual, per contact
  double min_cpa_m = 0.0;
};

Result<SimulatedManeuver> simulate_maneuver(const SimulatedManeuverQuery& q);

}  // namespace avk::app
