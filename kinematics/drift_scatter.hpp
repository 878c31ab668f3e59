#pragma once
// How fast a straight-line prediction's error grows, learned from the vehicle's own steady legs.
//
// A guidance predicting a held heading at a commanded speed expects the velocity over ground
// ground_velocity_for(heading, U, c, reference) (kinematics/speed_reference.hpp). On a real leg
// gusts, the speed loop's wander and the current's error make the vehicle's velocity differ from
// it; the model here is a constant velocity error per realisation, so the position error grows
// linearly: its standard deviation after τ seconds is rate · τ, along the heading and across it.
// The rates are the RMS over legs of each leg's least-squares velocity over ground minus the
// prediction, split along and across the held heading. The leg's velocity is its mean over the
// leg, which is what carries a prediction over a horizon as long as the leg; its GNSS noise
// (σ_gnss · sqrt(12 / n) / T, about 0.025 m/s for 5 s at 10 Hz and 0.3 m) is in the rates too, so
// longer legs measure them better.

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/current_estimate.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/water_current.hpp"

namespace avk::kinematics {

inline constexpr std::size_t kMinDriftScatterLegs = 3;

struct DriftScatter {
  double along_mps = 0.0;  // RMS velocity error along the held heading
  double cross_mps = 0.0;  // across it
  std::size_t legs = 0;
  double mean_leg_s = 0.0;  // the legs' mean duration: the horizon the rates were measured over
  friend bool operator==(const DriftScatter&, const DriftScatter&) = default;
};

// Legs with a commanded speed (water_speed_mps) > 0 against the prediction in the current c (none:
// still water) under the reference. Empty below kMinDriftScatterLegs such legs. Throws
// std::invalid_argument for a leg ground_velocity_mps refuses.
std::optional<DriftScatter> drift_scatter_of(const std::vector<SteadyLeg>& legs,
                                             const std::optional<WaterCurrent>& c,
                                             SpeedReference ref);

// The legs of several sets (missions) as one: each rate's mean square weighted by legs, the mean
// leg duration likewise. Empty for no legs.
std::optional<DriftScatter> pooled(const std::vector<DriftScatter>& parts);

}  // namespace avk::kinematics
