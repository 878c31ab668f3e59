#pragma once
// Maneuver evaluation as guidance asks for it (thesis §1.1, §6.1, §6.2): every candidate heading
// change predicted by one method (the vehicle's CKT, its black-box model, or the instantaneous
// assumption), placed at the vehicle's pose, scored by closest point of approach to each contact,
// and the choice. Also the evaluation of a maneuver in progress. Commands nothing.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/predict.hpp"
#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/maneuver.hpp"
#include "kinematics/maneuver_choice.hpp"
#include "kinematics/position_band.hpp"

namespace avk::app {

class Context;

// The navigation's position noise the band never narrows below (1 sigma, each axis): a GNSS fix
// of the class the M200 carries, and the simulator's default. Not yet measured per vehicle.
inline constexpr double kNavigationPositionSdM = 0.3;

struct ManeuverQuery {
  std::string vehicle_id;
  kinematics::Pose own;    // position (local grid) and heading now
  double speed_mps = 1.0;  // steady speed now
  std::vector<kinematics::Contact> contacts;
  // Also the station's live contacts: every other vehicle of its fleet (on its heading at its
  // speed) and every AIS contact it watches, at their positions now, after `contacts`.
  bool live_contacts = false;
  double standoff_m = 10.0;
  double horizon_s = 120.0;
  // Candidate heading changes (deg, + starboard); empty: -180..180 in candidate_step_deg.
  std::vector<double> candidates_deg;
  double candidate_step_deg = 5.0;
  // The speed of every candidate; none: the current speed.
  std::optional<double> candidate_speed_mps;
  PredictionMethod method = PredictionMethod::avk;
  std::optional<std::int64_t> model_id;  // model: this one; none: the vehicle's newest
  double corridor_share = kinematics::kDefaultCorridorShare;
  bool use_corridor = true;  // avk: judge by the corridor's nearer edge
  // The current (grid frame): every candidate drifts with it; or the station's live estimate;
  // or none (through the water). Neither: over ground wherever the station knows the current
  // (app/current.hpp query_current).
  std::optional<kinematics::WaterCurrent> current;
  bool live_current = false;
  bool no_current = false;
  // Which speed the vehicle's loop holds, over ground (true) or through the water; none: the
  // vehicle's, as the station identified it (app/vehicle_motion.hpp).
  std::optional<bool> speed_over_ground;
  // The choice: by risk (the default) with this limit, optionally keeping to starboard where
  // COLREGS rules 14 and 15 ask it; or the corridor rule (the smallest |dheading| whose corridor
  // edge clears the standoff).
  double max_risk = kinematics::kDefaultMaxRisk;
  bool prefer_starboard = false;
  bool corridor_rule = false;
  // The instantaneous method with the vehicle's band (scatter and current) about its ray; off:
  // the assumption as stated, the vehicle exactly on the ray.
  bool ray_band = false;
  // The yaw rate now (deg/s, + clockwise): each candidate starts turning at it (into a starboard
  // candidate when +, against it when -). avk: the table over initial yaw rate
  // (yaw_rate_table.hpp); model: the model started at that rate. None: from a steady course.
  std::optional<double> initial_yaw_rate_dps;
};

struct ManeuverEvaluation {
  ManeuverQuery query;  // with the live contacts added to its contacts
  // Who each live contact is (a vehicle id, or "AIS <MMSI> <name>"), in the order they follow
  // the request's own contacts.
  std::vector<std::string> live_contact_names;
  std::vector<kinematics::CandidateEvaluation> candidates;  // in the order asked
  std::optional<std::size_t> chosen;                        // index into candidates
  std::optional<std::int64_t> model_id;                     // model: the model that answered
  std::optional<std::string> table_source;                  // avk: "turns" or "imported"
  // avk: the times along the trajectories come from the recorded turns (else constant speed: an
  // imported table without timing).
  bool timed_by_turns = false;
  std::optional<kinematics::WaterCurrent> current;  // the drift added, and where it came from
  std::optional<std::string> current_source;
  std::string frame = "water";  // of every candidate's path: "ground" or "water"
  std::optional<std::array<double, 3>> current_covariance;  // (m/s)², [ee, en, nn]
  AnswerMotion motion;                // the speed reference and scatter the answer used
  kinematics::ManeuverChoice choice;  // the rule's account of the choice (risk rule)
};

// invalid_argument names the field as a JSON pointer of the request document (/own/speed_mps,
// /contacts/K/speed_mps, /standoff_m, /horizon_s, /candidates_deg/K, /candidate_step_deg,
// /candidate_speed_mps, /corridor, /current); not_found without a table (avk) or model (model),
// or without a live estimate of the current when it is asked for.
Result<ManeuverEvaluation> evaluate_maneuvers(Context& ctx, const ManeuverQuery& q);

struct OngoingQuery {
  std::string vehicle_id;
  kinematics::Pose start;     // where the maneuver was commanded
  double dheading_deg = 0.0;  // + starboard
  double speed_mps = 1.0;
  double elapsed_s = 0.0;                     // since it was commanded
  std::optional<kinematics::Point> measured;  // the position now
  PredictionMethod method = PredictionMethod::avk;
  std::optional<std::int64_t> model_id;
  double corridor_share = kinematics::kDefaultCorridorShare;
  double horizon_s = 120.0;  // how far the prediction runs
  std::optional<kinematics::WaterCurrent> current;
  bool live_current = false;
  bool no_current = false;
  std::optional<bool> speed_over_ground;
};

struct OngoingManeuver {
  OngoingQuery query;
  std::optional<kinematics::WaterCurrent> current;
  std::optional<std::string> current_source;
  kinematics::OngoingEvaluation evaluation;
  kinematics::TimedPath prediction;  // the whole placed prediction, to the horizon
  std::vector<double> half_width_m;  // the corridor per prediction point; empty without one
  std::vector<kinematics::Covariance2> covariance_m2;  // the position band per point
  std::string frame = "water";
  std::optional<std::array<double, 3>> current_covariance;
  AnswerMotion motion;
  std::optional<std::int64_t> model_id;
};

// What an answer assumes of the vehicle's motion: the request's speed reference, else the
// vehicle's; its straight-leg scatter.
// With missions given, from what those missions measured only (vehicle_motion).
AnswerMotion answer_motion(Context& ctx, const std::string& vehicle_id,
                           std::optional<bool> speed_over_ground,
                           std::span<const std::int64_t> missions = {});

// A table's answer as a timed maneuver in the normalised frame, with the corridor's half widths
// at corridor_share and the turns' spread at equal time (PredictedManeuver::along_sd_m,
// cross_sd_m): across from the corridor, along from the turns' timing spread at the commanded
// speed; both 1 sigma, widened for the few turns they are known from as the corridor is (the t
// quantile and sqrt(1 + 1/n) over the normal quantile, at 90 %).
kinematics::PredictedManeuver table_maneuver(const kinematics::TurnPrediction& t, double speed_mps,
                                             double dheading_deg, double corridor_share);

// The band's sources for an answer: the vehicle's straight-leg scatter and the current
// estimate's covariance.
kinematics::BandSources band_sources(
    const AnswerMotion& motion, const std::optional<std::array<double, 3>>& current_covariance);

// invalid_argument names the query parameter (x, dheading, speed, elapsed, horizon, mx,
// corridor, current); not_found as evaluate_maneuvers.
Result<OngoingManeuver> evaluate_ongoing(Context& ctx, const OngoingQuery& q);

}  // namespace avk::app
