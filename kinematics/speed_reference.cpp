#include "kinematics/speed_reference.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/angles.hpp"
#include "kinematics/water_frame.hpp"

namespace avk::kinematics {

const char* to_string(SpeedReference r) {
  return r == SpeedReference::over_ground ? "over_ground" : "through_water";
}

std::optional<SpeedReference> parse_speed_reference(std::string_view s) {
  if (s == "over_ground") return SpeedReference::over_ground;
  if (s == "through_water") return SpeedReference::through_water;
  return std::nullopt;
}

std::array<double, 2> ground_velocity_for(double heading_deg, double speed_mps,
                                          const WaterCurrent& current, SpeedReference ref) {
  const double h = deg_to_rad(heading_deg);
  const double he = std::sin(h), hn = std::cos(h);
  if (!(speed_mps > 0.0)) return {current.east_mps, current.north_mps};
  double along_mps = speed_mps;  // the speed through the water, k · U
  // The same loop gain a re-timed prediction uses (water_frame.hpp over_ground_scale).
  if (ref == SpeedReference::over_ground)
    along_mps = speed_mps * over_ground_scale({speed_mps * he, speed_mps * hn},
                                              {current.east_mps, current.north_mps});
  return {along_mps * he + current.east_mps, along_mps * hn + current.north_mps};
}

SpeedReferenceEvidence identify_speed_reference(const std::vector<SteadyLeg>& legs,
                                                const CurrentEstimate& c) {
  SpeedReferenceEvidence e;
  double og = 0.0, tw = 0.0, sep = 0.0;
  for (const SteadyLeg& leg : legs) {
    if (!(leg.water_speed_mps > 0.0)) continue;
    const auto v = ground_velocity_mps(leg);
    const double h = deg_to_rad(leg.heading_deg);
    const double he = std::sin(h), hn = std::cos(h);
    const double u = leg.water_speed_mps;
    const double r_og = std::hypot(v[0], v[1]) - u;
    const double r_tw = (v[0] - c.east_mps) * he + (v[1] - c.north_mps) * hn - u;
    const double c_along = c.east_mps * he + c.north_mps * hn;
    og += r_og * r_og;
    tw += r_tw * r_tw;
    sep += c_along * c_along;
    ++e.legs;
  }
  if (e.legs == 0) return e;
  const auto n = static_cast<double>(e.legs);
  e.rms_over_ground_mps = std::sqrt(og / n);
  e.rms_through_water_mps = std::sqrt(tw / n);
  e.separation_mps = std::sqrt(sep / n);
  const bool og_better = e.rms_over_ground_mps <= e.rms_through_water_mps;
  const double better = og_better ? e.rms_over_ground_mps : e.rms_through_water_mps;
  const double worse = og_better ? e.rms_through_water_mps : e.rms_over_ground_mps;
  if (e.legs >= kMinSpeedReferenceLegs && e.separation_mps >= kMinSpeedReferenceSeparationMps &&
      e.separation_mps >= kSpeedReferenceSeparation * better &&
      worse >= kSpeedReferenceRatio * better)
    e.identified = og_better ? SpeedReference::over_ground : SpeedReference::through_water;
  return e;
}

}  // namespace avk::kinematics
