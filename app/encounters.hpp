#pragma once
// The encounter test bench: the thesis' question "does assuming instantaneous turns
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

// A scenario's name names its rows in every result table.
inline constexpr std::size_t kMaxScenarioNameBytes = 256;

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
  // What the vehicle did before the command: the simulated time it took to settle (ConditionSet
  // with the held course), and its true heading and speed at the command.
  double settle_s = 0.0;
  double heading_at_command_deg = 0.0;
  double speed_at_command_mps = 0.0;
};

// invalid_argument names the field (own_speed, dheading, speed, horizon, contacts/K/...).
Result<SimulatedManeuver> simulate_maneuver(const SimulatedManeuverQuery& q);

// The bench over a scenario file: every candidate of every scenario flown once (shared by all
// methods), each method's choice from evaluate_maneuvers and the flight of the chosen candidate.
struct EncounterBenchQuery {
  std::string vehicle_id;  // the database's vehicle whose CKT and model the methods use
  sim::SimSetup setup;     // the simulated plant, controller and disturbances
  std::uint64_t seed = 1;  // every flight of the bench (so all candidates meet the same sea)
  std::vector<PredictionMethod> methods{PredictionMethod::avk, PredictionMethod::model,
                                        PredictionMethod::instantaneous};
  double candidate_step_deg = 5.0;  // candidates -180..180 in this step
  int threads = 2;                  // scenarios flown in parallel; results do not depend on it
  // Every method's candidates drift with the current the station estimated for the vehicle (its
  // newest mission's, app/current.hpp) when it is told apart from still water: the knowledge a
  // vehicle in that sea has. Off: predictions through the water (or over ground, from a table of
  // ground turns) without drift.
  bool use_estimated_current = true;
  // Sea realisations: every candidate of every scenario is flown once per seed (the same
  // choices, different gusts, waves and sensor noise); each (scenario, seed) is one row of the
  // results. Empty: `seed` alone.
  std::vector<std::uint64_t> sea_seeds;
  // The choice rule every method uses (maneuvers.hpp).
  double max_risk = kinematics::kDefaultMaxRisk;
  bool prefer_starboard = false;
  bool corridor_rule = false;
  std::optional<bool> speed_over_ground;  // none: the vehicle's
  // The instantaneous method with the vehicle's band about its ray (ManeuverQuery::ray_band).
  bool ray_band = false;
};

struct EncounterMethodResult {
  PredictionMethod method = PredictionMethod::avk;
  std::optional<double> chosen_dheading_deg;   // none: no candidate cleared (course held)
  std::optional<double> predicted_cpa_m;       // of the chosen candidate's predicted path
  std::optional<double> predicted_edge_cpa_m;  // avk: of its corridor's nearer edge
  // Flown: the chosen candidate, or the course held (dheading 0) when none was chosen.
  double actual_cpa_m = 0.0;
  bool violation = false;                      // actual < standoff
  bool no_maneuver_while_one_existed = false;  // none chosen, yet some candidate flew clear
  bool unsafe_while_safe_existed = false;      // chose one that violated, yet one flew clear
  std::optional<double> chosen_risk;           // the chosen candidate's predicted risk
  std::string colregs_rule;                    // "14" / "15" when the choice kept to starboard
  // Where the flown vehicle was at its CPA against where the chosen prediction put it at that
  // time: along the predicted path's direction (+ ahead) and across it (+ right), m.
  std::optional<double> along_error_m;
  std::optional<double> cross_error_m;
};

struct EncounterScenarioResult {
  std::string name;  // the scenario's, with " @sea N" when several sea seeds are flown
  std::uint64_t sea_seed = 1;
  double standoff_m = 0.0;
  std::vector<double> candidates_deg;
  std::vector<double> flown_cpa_m;             // per candidate: the actual CPA over contacts
  double course_held_cpa_m = 0.0;              // flown with dheading 0
  bool safe_existed = false;                   // some candidate's flown CPA >= standoff
  std::vector<EncounterMethodResult> methods;  // one per available method, in the query's order
};

struct RiskBin {
  double lo = 0.0, hi = 0.0;  // predicted risk in [lo, hi)
  int candidates = 0;
  double mean_predicted = 0.0;
  double observed_rate = 0.0;  // share of those candidates that flew inside the standoff
};
// The bins' edges: fine at the small risks a choice is made at.
inline constexpr double kRiskBinEdges[] = {0.0, 0.01, 0.05, 0.1, 0.2, 0.3,  0.4,
                                           0.5, 0.6,  0.7,  0.8, 0.9, 0.99, 1.0000001};

struct EncounterMethodSummary {
  PredictionMethod method = PredictionMethod::avk;
  bool available = true;
  std::string note;  // why the method is not available (no model, no table)
  int scenarios = 0;
  int violations = 0;
  double violation_rate = 0.0;
  int no_maneuver = 0;
  int no_maneuver_while_one_existed = 0;
  int unsafe_while_safe_existed = 0;
  std::optional<double> mean_abs_dheading_deg;  // over the scenarios with a choice
  // Predicted minus actual CPA of the chosen candidates.
  std::optional<double> mean_cpa_error_m;
  std::optional<double> mean_abs_cpa_error_m;
  // The position error at the flown CPA of the chosen candidates (mean absolute, m).
  std::optional<double> mean_abs_along_error_m;
  std::optional<double> mean_abs_cross_error_m;
  // The predicted risk against the observed violation rate over every flown candidate (all
  // scenarios, all sea seeds): is a 10 % risk violated one time in ten?
  std::vector<RiskBin> calibration;
  std::optional<std::int64_t> model_id;  // model: the model that answered
};

struct EncounterBench {
  std::optional<kinematics::WaterCurrent> current;  // the drift every method's candidates had
  std::vector<EncounterScenarioResult> scenarios;
  std::vector<EncounterMethodSummary> summary;  // one per method asked, in order
  std::size_t flights = 0;                      // maneuvers flown
};

// invalid_argument names the field (methods, candidate_step, threads); a method the vehicle
// cannot answer (no model, no table) is reported unavailable in its summary, not an error.
Result<EncounterBench> run_encounter_bench(Context& ctx, const EncounterFile& file,
                                           const EncounterBenchQuery& q);

// A reproducible scenario file (docs/encounter-format.md, "Generating scenarios"): count
// scenarios cycling through head-on, crossing from starboard, crossing from port, overtaking,
// being overtaken and several contacts; every contact aimed near a point of own track 15-60 s
// ahead, so holding course violates the standoff. invalid_argument for count < 1.
Result<EncounterFile> generate_encounters(std::uint64_t seed, int count);

// The file as JSON text (the format parse_encounter_file reads).
std::string encounter_file_json(const EncounterFile& file);

}  // namespace avk::app
