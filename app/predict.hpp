#pragma once
// One predicted turn, as guidance asks for it: by the vehicle's CKT (AVK), its black-box yaw
// model, or the instantaneous-turn assumption, in the normalised frame or placed at a pose.
// Every front end answers through here, so the same database and question give one trajectory.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/geometry.hpp"
#include "kinematics/position_band.hpp"
#include "kinematics/water_current.hpp"

namespace avk::app {

class Context;

enum class PredictionMethod { avk, model, instantaneous };
const char* to_string(PredictionMethod m);
std::optional<PredictionMethod> prediction_method_from_string(const std::string& s);

// What an answer assumed of the vehicle's motion: the speed its loop holds and how a straight
// prediction's error grows, and where each came from ("identified", "default", "query").
struct AnswerMotion {
  bool speed_over_ground = true;
  std::string speed_reference_source = "default";
  kinematics::MotionScatter scatter;
  double position_sd_m = 0.0;  // the navigation's position noise
  std::string scatter_source = "default";
};

struct PredictQuery {
  std::string vehicle_id;
  double speed_mps = 0.0;
  double dheading_deg = 0.0;  // + right, - left
  PredictionMethod method = PredictionMethod::avk;
  std::optional<std::int64_t> model_id;   // model: this one; none: the vehicle's latest
  bool use_speed_model = false;           // model: let the model's speed response slow the turn
  double completion_threshold_deg = 5.0;  // model: the turn ends this close to the goal
  std::optional<kinematics::Pose> pose;   // where the turn starts; none: the normalised frame
  // avk: the share of the vehicle's turns the corridor holds.
  double corridor_share = kinematics::kDefaultCorridorShare;
  // The current the turn is made in (grid frame, m/s toward east/north): the prediction through
  // the water is carried by its drift over the prediction's time. In the normalised frame (no
  // pose) the start heading is north, so the current is read as if the turn began heading north.
  std::optional<kinematics::WaterCurrent> current;
  bool live_current = false;  // the current: the station's latest estimate for the vehicle
  bool no_current = false;    // nothing added: the path through the water
  // Which speed the vehicle's loop holds in the current, over ground (true: the turn is re-timed,
  // kinematics::retimed_over_ground) or through the water (false: the path through the water
  // carried by c·t); none: the vehicle's, as the station knows it (AnswerMotion).
  std::optional<bool> speed_over_ground;
  // avk: the vehicle's table of collection and harvested turns, not collection turns alone.
  bool include_harvested = false;
  // The yaw rate when the turn is commanded (deg/s, + clockwise, as headings turn; for a right
  // turn + is into the turn, for a left turn -). None: from a steady course (the 2-D table).
  // avk: the vehicle's table over initial yaw rate (yaw_rate_table.hpp); model: the model started
  // turning at that rate.
  std::optional<double> initial_yaw_rate_dps;
  // The speed commanded with the new heading (u1); speed_mps is the speed held before the turn
  // (u0). Empty (or equal to speed_mps): a constant-speed turn.
  std::optional<double> speed_after_mps;
  // A stored mission, or one stored turn, the answer must not have learnt from: a past turn is
  // shown as it would have been predicted without it (Replay: its mission; Live: the turn just
  // finished), never against a table that holds it. avk: a table of the vehicle's other ok turns
  // (constant-speed turns from a steady course only); model: the given or latest model not
  // trained on that mission (on the turn's mission).
  std::optional<std::int64_t> without_mission_id;
  std::optional<std::int64_t> without_turn_id;
};

// How a turn with a speed change was answered: measured cells of that (u0, u1) pair, the
// constant-speed turn at u0 re-timed by a speed response, or the yaw model's speed model.
enum class SpeedChangeSource { measured, retimed, model };
const char* to_string(SpeedChangeSource s);

struct Prediction {
  PredictQuery query;
  kinematics::Polyline trajectory;  // reflected for a left turn; placed when a pose was given
  // avk: the table's expected advance and transfer at the end of the turn.
  std::optional<double> advance_m;
  std::optional<double> transfer_m;
  // avk: answered by one cell of the table (not interpolated), and whether the heading change
  // lies outside the table's (the nearest cell's shape carried by a fitted arc).
  std::optional<bool> exact_cell;
  std::optional<bool> extrapolated;
  std::optional<std::int64_t> model_id;     // model: the model that answered
  std::optional<std::int64_t> snapshot_id;  // avk: the imported table that answered, if one did
  std::optional<std::string> table_source;  // avk: "turns" or "imported"
  // avk: the lateral band about the trajectory that holds corridor_share of the vehicle's turns
  // (kinematics/corridor.hpp), in the trajectory's frame; none when the table has no spread (a
  // cell of one turn, or an imported table without corridors).
  std::optional<kinematics::CorridorBand> corridor;
  bool short_of_goal = false;  // avk: a cell that answered holds turns that stopped short
  // avk: the frame of the turns the table was built from (kinematics::TableFrame): a water-frame
  // table predicts through the water, so the current belongs in the query.
  std::optional<std::string> table_frame;
  // The current whose drift was added, and where it came from (app/current.hpp query_current:
  // "query", "live", "still_water", "unknown", "none"); the frame the trajectory is in ("ground":
  // over ground, where the station knows the current; "water": through the water), the
  // estimate's covariance of (east, north) in (m/s)² [ee, en, nn], and the speed reference the
  // current was applied with.
  std::optional<kinematics::WaterCurrent> current;
  std::optional<std::string> current_source;
  std::string frame = "water";
  std::optional<std::array<double, 3>> current_covariance;
  AnswerMotion motion;
  // avk with an initial yaw rate: where the answer came from (measured, model or interpolated)
  // and whether the rate lay outside the table's yaw-rate range (answered by the nearest slice).
  std::optional<std::string> cell_source;
  std::optional<bool> yaw_rate_clamped;
  // With a speed change: how it was answered, and for a re-timed answer which speed response
  // re-timed it ("measured": the vehicle's stored speed-change turns; "model": its yaw model's
  // speed model).
  std::optional<SpeedChangeSource> speed_change_source;
  std::optional<std::string> speed_response;
};

// invalid_argument names the parameter (speed, dheading, model, speed_model, current); not_found
// when there is no live estimate of the current (live_current); not_found when the
// vehicle has no table (avk) or the model does not exist (model).
Result<Prediction> predict(Context& ctx, const PredictQuery& q);

// The prediction of a given table (a CKT file), interpolated exactly: `avk ckt query`.
Result<Prediction> predict_with_table(const kinematics::Ckt& table, const PredictQuery& q);

// The instantaneous-turn assumption in the CKT's frame (from the origin heading north): on the
// new heading at once, for duration_s of travel (20 s as drawn; a maneuver's horizon).
kinematics::Polyline instantaneous_turn_ray(double speed_mps, double dheading_deg,
                                            double duration_s = 20.0);

}  // namespace avk::app
