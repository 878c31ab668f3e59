#pragma once
// The current a mission flew in, estimated from its own navigation: the steady legs before each
// turn, where the ConditionSet held course and speed, give the velocity over ground on many
// headings (kinematics/current_estimate.hpp).

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/current_view.hpp"
#include "app/result.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/turn_sequence.hpp"
#include "kinematics/water_current.hpp"

namespace avk::app {

class Context;

// How much of the steady stretch before each turn is used: the last leg_s seconds before the
// command during which the desired heading and speed stayed as they were at the command.
inline constexpr double kSteadyLegS = 8.0;
inline constexpr double kMinSteadyLegS = 3.0;

struct MissionCurrent {
  std::int64_t mission_id = 0;
  std::size_t turns = 0;      // turns of the mission
  std::size_t legs_used = 0;  // steady legs found before them
  kinematics::CurrentEstimateResult result;
  // From the longer steady stretches (steady_stretches_before), legs only: which speed the loop
  // held, judged in the estimated current (none without an estimate), and the drift scatter of the
  // predictions a guidance would have made (app/vehicle_motion.hpp).
  std::size_t motion_legs = 0;
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference;
  std::optional<kinematics::DriftScatter> drift_scatter;
};

// not_found for an unknown mission.
Result<MissionCurrent> estimate_mission_current(Context& ctx, std::int64_t mission_id,
                                                double leg_s = kSteadyLegS);

// The current from the mission's turns (thesis §6.3): each ok turn over ground against the
// prediction through the water of a table built from the vehicle's OTHER missions (their turns in
// the water frame where known), both from the command; under a uniform current the difference
// grows as c·t (kinematics/current_estimate.hpp estimate_current_from_turns). A check on the
// steady-leg estimate, independent of it; whatever the table gets wrong the same way on every
// heading goes into it. not_found for an unknown mission or when the other missions hold no
// turns; turns at speeds the table does not hold are left out (legs_used counts the turns used).
Result<MissionCurrent> estimate_mission_current_from_turns(Context& ctx, std::int64_t mission_id);

// An estimate is taken out of the turns only when it is told apart from still water: at least
// kMinCurrentMps and twice its 1-sigma speed. Below that, removing a "current" that is noise
// would only move the turns.
inline constexpr double kMinCurrentMps = 0.03;
// A current asked for in a query: far past any water a small surface vehicle works in.
inline constexpr double kMaxCurrentMps = 5.0;
bool current_is_significant(const kinematics::CurrentEstimate& e);

kinematics::WaterCurrent water_current(const kinematics::CurrentEstimate& e);

// Each turn (raw, over ground; by id) in the water frame under the current, normalised: the
// form the table reads. Turns that cannot be moved (already normalised) are left out.
std::vector<std::pair<std::int64_t, kinematics::TurnSequence>> water_frame_turns(
    const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& raw_turns,
    kinematics::WaterCurrent c);

struct AppliedCurrent {
  MissionCurrent current;
  std::optional<CurrentView> stored;  // none when there is no estimate
  std::size_t water_turns = 0;        // ok turns given a water-frame form (0: not significant)
};

// Estimates the mission's current from its steady legs and stores it; when it is significant its
// ok turns get their water-frame form, so the vehicle's table is built from them. Without an
// estimate nothing is stored and the turns keep their ground form. not_found for an unknown
// mission.
Result<AppliedCurrent> apply_mission_current(Context& ctx, std::int64_t mission_id,
                                             double leg_s = kSteadyLegS);

// The current a query asks to be predicted in: the given one (validated: finite, at most
// kMaxCurrentMps), the station's live estimate (live), or none. invalid_argument names `field`
// for a bad or doubly given current; not_found when live is asked and there is no estimate.
// invalid_argument naming `field` unless the current is finite and at most kMaxCurrentMps.
std::optional<Error> check_current(const kinematics::WaterCurrent& c, const std::string& field);

// The current an answer drifts with, and the frame the answer is in.
// - Asked for (`given`): that current; over ground.
// - `live`: the station's latest estimate for the vehicle, significant or not; not_found when
//   there is none.
// - `none`: nothing added: the path through the water (for a table of water-frame turns).
// - Not asked (the default): over ground wherever the station can say so: the latest estimate
//   when it is significant (source "live"); still water when the estimate is not told apart from
//   it (source "still_water", nothing added, over ground all the same); through the water when
//   the vehicle has no estimate at all (source "unknown", frame "water"), which is said.
struct QueryCurrent {
  std::optional<kinematics::WaterCurrent> current;
  std::optional<std::string> source;  // "query", "live", "still_water", "unknown", "none"
  std::string frame = "water";        // "ground" or "water"
  // The estimate's covariance of (east, north) in (m/s)², [ee, en, nn]: live and automatic
  // answers carry the uncertainty of the current they drift with.
  std::optional<std::array<double, 3>> covariance;
};
Result<QueryCurrent> query_current(Context& ctx, const std::string& vehicle_id,
                                   const std::optional<kinematics::WaterCurrent>& given, bool live,
                                   const std::string& field, bool none = false);

// The mission's stored estimate (none without one); not_found for an unknown mission.
Result<std::optional<CurrentView>> stored_mission_current(Context& ctx, std::int64_t mission_id);

// The station's estimate for a vehicle: the newest stored estimate of any of its missions (the
// running one's is updated at every turn). not_found when it has none.
Result<CurrentView> vehicle_current(Context& ctx, const std::string& vehicle_id);

}  // namespace avk::app
