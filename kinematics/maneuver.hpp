#pragma once
// Choosing an avoidance maneuver by predicted closest point of approach (CPA), thesis §1.1 and
// §6.1: each candidate heading change is a predicted trajectory in time; each contact moves on a
// straight line; the candidate clears when its CPA to every contact is at least the standoff.
//
// Frames: the local grid (x east, y north, metres), headings in degrees clockwise from north,
// times in seconds from the moment the maneuver is commanded (t = 0).

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/position_band.hpp"
#include "kinematics/timed_path.hpp"
#include "kinematics/turn_timing.hpp"
#include "kinematics/water_current.hpp"

namespace avk::kinematics {

// A contact on a straight line at constant speed; its position at t = 0. The 1-sigma
// uncertainties of what is known of it (0: exact) widen the risk of a close approach.
struct Contact {
  double x_m = 0.0;
  double y_m = 0.0;
  double course_deg = 0.0;  // clockwise from north
  double speed_mps = 0.0;
  double position_sd_m = 0.0;
  double course_sd_deg = 0.0;
  double speed_sd_mps = 0.0;
};
Point contact_position(const Contact& c, double t_s);

// A predicted maneuver in the normalised frame (start at the origin heading north; a left turn
// already reflected): the path in time until it has settled on its new heading, and the lateral
// half width of the uncertainty corridor at each point (empty: no corridor).
//
// The spread of the recorded turns about the prediction at equal time, per path point: along
// the path (being early or late: the turns' timing spread) and across it (the corridor's lateral
// spread), 1 sigma, already widened for the few turns it is known from. Empty: none known (the
// model, the ray). Past the turn (points from turn_points on) the spread is held and the
// vehicle's straight-leg scatter grows on top of it (position_band.hpp).
struct PredictedManeuver {
  double dheading_deg = 0.0;  // signed: + starboard
  double speed_mps = 0.0;
  TimedPath path;
  std::vector<double> half_width_m;  // empty, or one per path point
  bool timed_by_turns = false;       // the times come from recorded turns, not constant speed
  std::vector<double> along_sd_m;    // empty, or one per path point
  std::vector<double> cross_sd_m;    // empty, or one per path point
  // How many leading points are the turn itself; the growth of the straight-leg scatter starts
  // at the last of them. 1: from the command (a prediction without recorded turns).
  std::size_t turn_points = 1;
};

// A normalised trajectory given times along it: from the timing when there is one, else at
// constant speed. Half widths, when given, are per trajectory vertex (CorridorBand::half_width_m).
PredictedManeuver timed_maneuver(double dheading_deg, double speed_mps, const Polyline& trajectory,
                                 const std::optional<TurnTiming>& timing,
                                 std::vector<double> half_width_m = {});

// The path continued from its last point along its final heading (dheading in the normalised
// frame) at speed_mps up to horizon_s, so a CPA looks as far ahead as asked. The corridor's last
// half width and the last spreads are carried along. Paths already reaching the horizon are cut
// there.
PredictedManeuver extended_to_horizon(PredictedManeuver m, double horizon_s);

// The normalised path placed at a pose (rotated to its heading, translated to its position).
TimedPath placed(const TimedPath& normalized, const Pose& pose);

struct Approach {
  double distance_m = 0.0;
  double time_s = 0.0;
};

// The closest approach over the path's time span (exact: the relative motion is linear on each
// segment). A path of one point stands still there. Throws std::invalid_argument for an empty
// path.
Approach closest_approach(const TimedPath& own, const Contact& contact);

// The conservative figure: the smallest distance to the contact minus the corridor's half width
// at that time (floored at 0), i.e. the distance from the corridor's nearer edge. Evaluated at each
// segment's ends and at the segment's closest approach. Throws std::invalid_argument when the
// half widths do not match the path.
Approach closest_approach_of_corridor(const TimedPath& own, const std::vector<double>& half_width_m,
                                      const Contact& contact);

struct ContactApproach {
  Approach cpa;                      // of the predicted path
  std::optional<Approach> edge_cpa;  // of the corridor's nearer edge, when there is a corridor
  double risk = 0.0;                 // P(CPA < standoff) under the band (approach_risk)
};

struct ManeuverProblem {
  Pose own;  // position and heading now, steady
  std::vector<Contact> contacts;
  double standoff_m = 10.0;
  double horizon_s = 120.0;
  // Judge a candidate by its corridor's nearer edge when it has a corridor (the corridor rule).
  bool use_corridor = true;
  // The current the own vehicle turns in (grid frame): each candidate, predicted through the
  // water, drifts with it; the contacts' courses and speeds are over ground already.
  std::optional<WaterCurrent> current;
  // How the current carries a candidate: a vehicle whose speed loop holds the commanded speed
  // over ground flies each part of the path at the speed over ground it would make in still
  // water (its speed through the water changes); one holding speed through the water is carried
  // by c·t on top of its still-water path.
  bool speed_over_ground = true;
  // The sources of the position band beyond the turns' own spread (position_band.hpp).
  BandSources band;
};

struct CandidateEvaluation {
  double dheading_deg = 0.0;
  double speed_mps = 0.0;
  TimedPath path;                    // world frame, to the horizon
  std::vector<double> half_width_m;  // per path point; empty without a corridor
  std::vector<ContactApproach> contacts;
  double min_cpa_m = 0.0;                // over contacts
  std::optional<double> min_edge_cpa_m;  // over contacts, with a corridor
  bool clears = false;  // the judged figure (edge when used and present) >= standoff for all
  std::vector<Covariance2> covariance_m2;  // the position band, per path point
  // P(the CPA to some contact < standoff): 1 − Π(1 − risk of each contact), the contacts taken
  // as independent of each other.
  double risk = 0.0;
};

// The normalised prediction placed at the pose and carried by the current as the vehicle's speed
// loop flies it (water_frame.hpp: drifted through the water, retimed_over_ground over ground),
// to the horizon, with its per-point values.
PredictedManeuver placed_over_ground(const PredictedManeuver& normalized, const Pose& pose,
                                     const std::optional<WaterCurrent>& current,
                                     bool speed_over_ground, double horizon_s);

// One candidate against the problem's contacts.
CandidateEvaluation evaluate_candidate(const ManeuverProblem& problem,
                                       const PredictedManeuver& normalized);

// The rule: the smallest |dheading| that clears; between equal |dheading|, starboard (+). None
// when no candidate clears.
std::optional<std::size_t> choose_maneuver(const std::vector<CandidateEvaluation>& candidates);

// -180, -180 + step, ..., 180 (73 candidates at the default 5 deg). Throws std::invalid_argument
// unless 0 < step <= 180.
std::vector<double> candidate_dheadings_deg(double step_deg = 5.0);

// A maneuver in progress (§6.2): where the vehicle should be after elapsed_s along the placed
// prediction, what remains of it, and how far a measured position is from it.
struct OngoingEvaluation {
  double elapsed_s = 0.0;
  Point expected;                       // on the prediction at elapsed_s
  TimedPath remaining;                  // from expected to the end of the prediction
  std::optional<double> half_width_m;   // the corridor at elapsed_s
  std::optional<double> deviation_m;    // measured to expected (along-time error)
  std::optional<double> cross_track_m;  // measured to the nearest point of the whole prediction
  // The position band at elapsed_s (interpolated in time between the path's points) and its
  // ellipse at the band's share; empty without a band.
  std::optional<Covariance2> band_m2;
  std::optional<BandEllipse> band_ellipse;
  std::optional<bool> inside_band;  // the measured position within the band's ellipse
  // Where the vehicle is judged inside: the band when there is one, else the cross-track within
  // the corridor's half width. The corridor alone is the recorded turns' spread, 0 m at the
  // command where they all start together, so any navigation noise would read "outside"; the
  // band adds that noise and the straight-leg scatter.
  std::optional<bool> inside_corridor;
};

// The band of a share about a placed path, one covariance per path point (position_band).
struct OngoingBand {
  std::vector<Covariance2> covariance_m2;
  double share = 0.9;
};

// Throws std::invalid_argument for an empty path, mismatched half widths or band, a share
// outside (0, 1), or a negative or non-finite elapsed time. Past the path's end the expected
// position is its last point.
OngoingEvaluation evaluate_ongoing(const TimedPath& placed_path,
                                   const std::vector<double>& half_width_m, double elapsed_s,
                                   std::optional<Point> measured,
                                   const std::optional<OngoingBand>& band = std::nullopt);

}  // namespace avk::kinematics
