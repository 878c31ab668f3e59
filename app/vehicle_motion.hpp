#pragma once
// What the station has learned of how a vehicle moves on a held heading, from its own steady legs:
// which speed its speed loop holds (over ground or through the water,
// kinematics/speed_reference.hpp), how fast a straight-line prediction's error grows
// (kinematics/drift_scatter.hpp), and the current it was last seen in. Each mission's legs are
// judged where its current is estimated (app/current.hpp, app/current_tracker.hpp) and stored with
// that estimate; the vehicle's answer gathers its missions'.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/current_view.hpp"
#include "app/result.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"

namespace avk::app {

class Context;

// Until a vehicle's legs identify it, its loop is taken to hold the speed over ground: the M200's
// frontseat runs pMarinePID on the GNSS speed, and so does the simulator (sim/sim_vehicle.cpp:
// MarinePid's incremental speed loop on the navigation's speed, the truth's speed over ground).
inline constexpr kinematics::SpeedReference kDefaultSpeedReference =
    kinematics::SpeedReference::over_ground;

// The drift scatter until one is measured: 0.10 m/s along the heading, 0.05 m/s across it. Along
// is the larger because a speed loop wanders around its set speed after every change (the
// simulated M200's legs in still water scatter by about 0.09 m/s along and 0.05 m/s across); across
// is the GNSS noise of a short leg's slope and the heading's wander. Larger rather than smaller:
// a guidance that trusts a straight line too much keeps too little margin.
inline constexpr kinematics::DriftScatter kDefaultDriftScatter{0.10, 0.05, 0, 0.0};

// A mission's legs judged in its current: which speed the loop held (legs and the estimate; none
// without an estimate), and the drift scatter of the predictions a guidance would have made on
// them: the identified reference (else kDefaultSpeedReference) in the current when it is
// significant (current_is_significant; else still water, as a guidance would take it).
struct LegMotion {
  std::optional<kinematics::SpeedReferenceEvidence> speed_reference;
  std::optional<kinematics::DriftScatter> drift_scatter;
};
LegMotion leg_motion(const std::vector<kinematics::SteadyLeg>& legs,
                     const std::optional<kinematics::CurrentEstimate>& current);

struct MotionSpeedReference {
  kinematics::SpeedReference value = kDefaultSpeedReference;
  std::string source = "default";  // "identified" or "default"
  // The evidence shown and its mission: the newest mission that identified a reference; by
  // default, the newest one evaluated (undetermined); none when no mission was.
  std::optional<std::int64_t> mission_id;
  std::optional<kinematics::SpeedReferenceEvidence> evidence;
  // How the vehicle's evaluated missions came out.
  std::size_t missions_over_ground = 0;
  std::size_t missions_through_water = 0;
  std::size_t missions_undetermined = 0;
};

struct MotionDriftScatter {
  kinematics::DriftScatter scatter = kDefaultDriftScatter;
  std::string source = "default";  // "measured" (pooled over missions by legs) or "default"
  std::size_t missions = 0;        // the missions pooled
};

struct VehicleMotion {
  std::string vehicle_id;
  MotionSpeedReference speed_reference;
  MotionDriftScatter drift_scatter;
  // The newest estimate of the current that is told apart from still water; none when there is
  // none.
  std::optional<CurrentView> current;
};

// The newest identification wins (conditions and the vehicle's setup change; the counts show
// whether missions agree); the drift scatter is pooled over every mission that measured one (RMS
// pooled by legs: more legs, steadier rates). not_found for a vehicle the station neither drives
// nor has stored. With missions given, only what those missions measured counts (an evaluation
// on held-out missions must not learn from them).
Result<VehicleMotion> vehicle_motion(Context& ctx, const std::string& vehicle_id,
                                     std::span<const std::int64_t> missions = {});

}  // namespace avk::app
