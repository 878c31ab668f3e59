#pragma once
// Which speed a vehicle's speed loop holds, learned from its own steady legs.
//
// On a steady leg v_ground = w · h + c, with h = (sin ψ, cos ψ) the heading's unit vector, w the
// speed through the water and c the current. A loop that holds the speed OVER GROUND (a GNSS speed
// fed to pMarinePID, as on the M200) makes |v_ground| = U, the commanded speed; one that holds the
// speed THROUGH THE WATER (a water-speed sensor, or thrust mapped open loop from the commanded
// speed) makes (v_ground − c) · h = U. The current c comes from the legs' components across the
// heading (kinematics/current_estimate.hpp), which neither hypothesis touches, so each leg gives a
// residual under each hypothesis. The two differ on a leg by about c · h: only a current with a
// clear component along the legs' headings can tell them apart.

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "kinematics/current_estimate.hpp"
#include "kinematics/water_current.hpp"

namespace avk::kinematics {

enum class SpeedReference { over_ground, through_water };
const char* to_string(SpeedReference r);  // "over_ground", "through_water"
std::optional<SpeedReference> parse_speed_reference(std::string_view s);

// How far a guidance should expect the vehicle to go over ground per second on a held heading at
// a commanded speed, in a current: (east, north) m/s.
//   through_water: U · h + c.
//   over_ground:   k · U · h + c with k > 0 such that |k · U · h + c| = U, i.e.
//                  k · U = −c · h + sqrt(U² − (c · n)²), n the heading's normal.
// When the current across the heading exceeds U no k makes the speed over ground U; then
// sqrt(...) is taken as 0 (the vehicle stems the current along the heading as best it can), and
// k is clamped to [kMinSpeedLoopGain, kMaxSpeedLoopGain]: a speed loop asks its thrusters for
// neither less than a quarter nor more than four times the commanded speed through the water.
// A speed of 0 or less drifts with the current.
inline constexpr double kMinSpeedLoopGain = 0.25;
inline constexpr double kMaxSpeedLoopGain = 4.0;
std::array<double, 2> ground_velocity_for(double heading_deg, double speed_mps,
                                          const WaterCurrent& current, SpeedReference ref);

// The rule (identify_speed_reference): a reference is identified when
//  - there are at least kMinSpeedReferenceLegs legs,
//  - the hypotheses differ: the RMS over legs of c · h (separation_mps) is at least
//    kMinSpeedReferenceSeparationMps and at least kSpeedReferenceSeparation times the smaller
//    residual RMS (the legs' speed noise under the better hypothesis: if the loop held that speed,
//    its residual is the noise), and
//  - the worse hypothesis' residual RMS is at least kSpeedReferenceRatio times the better's.
// Otherwise it is undetermined (still water, legs all across the current, or noise too large).
// The better residual is an upper bound on the noise: it also holds what both hypotheses share,
// such as a speed loop still settling after a turn (the simulated M200 makes 0.38-0.42 m/s of a
// commanded 0.5 on legs that are otherwise steady), which is why 1.5 and not more; the ratio test
// is the one that tells the hypotheses apart.
inline constexpr std::size_t kMinSpeedReferenceLegs = 3;
inline constexpr double kMinSpeedReferenceSeparationMps = 0.02;
inline constexpr double kSpeedReferenceSeparation = 1.5;
inline constexpr double kSpeedReferenceRatio = 2.0;

struct SpeedReferenceEvidence {
  std::size_t legs = 0;  // legs with a commanded speed > 0
  // RMS over legs of |v_ground| − U and of (v_ground − c) · h − U.
  double rms_over_ground_mps = 0.0;
  double rms_through_water_mps = 0.0;
  // RMS over legs of c · h: what separates the hypotheses.
  double separation_mps = 0.0;
  std::optional<SpeedReference> identified;  // none: undetermined
  friend bool operator==(const SpeedReferenceEvidence&, const SpeedReferenceEvidence&) = default;
};

// Each leg's velocity over ground (ground_velocity_mps), its held heading and commanded speed
// (water_speed_mps, the speed the loop was asked to hold), against the current c estimated from
// the legs' cross-heading components. Throws std::invalid_argument for a leg ground_velocity_mps
// refuses.
SpeedReferenceEvidence identify_speed_reference(const std::vector<SteadyLeg>& legs,
                                                const CurrentEstimate& c);

}  // namespace avk::kinematics
