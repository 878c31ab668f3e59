#pragma once
// The ranges a navigation value read from outside the station must lie in, shared by every reader
// of such input: NMEA sentences from a frontseat (vehicle/nmea.cpp), pLogger postings
// (vehicle/alog.cpp) and MCAP recordings (app/mission_mcap.cpp). One definition, so that the
// readers agree on what is plausible, and a mission imported from a log can be exported and
// imported again. Beyond a quantity's own limits (a heading), the bounds are far outside anything
// a small boat reports: they catch garbage that passed a checksum or a CRC (a firmware bug, an
// edited file), not unusual motion.

#include <string>

#include "vehicle/local_grid.hpp"

namespace avk::vehicle {

// Both bounds included.
struct ValueRange {
  double low = 0.0;
  double high = 0.0;

  // False for NaN.
  constexpr bool contains(double v) const { return v >= low && v <= high; }
};

// "[low, high]", the bounds written as the station writes numbers ("[0.0, 360.0]").
std::string to_string(const ValueRange& r);

// Degrees clockwise from north. Exactly 360 is in: a frontseat rounding 359.9999997 writes it.
inline constexpr ValueRange kHeadingRange_deg{0.0, 360.0};
// A speed, m/s: over ground, commanded or desired.
inline constexpr ValueRange kSpeedRange_mps{0.0, 100.0};
// One component of a velocity, m/s.
inline constexpr ValueRange kVelocityRange_mps{-100.0, 100.0};
// A rate of turn, deg/s: above the full scale of MEMS gyros.
inline constexpr ValueRange kRateRange_dps{-5000.0, 5000.0};
// A local grid coordinate, m. No point of the earth lies farther from the datum than the earth's
// diameter, so a coordinate beyond it is no position.
inline constexpr ValueRange kGridRange_m{-2.0 * kWgs84SemiMajorAxis_m, 2.0 * kWgs84SemiMajorAxis_m};
// The station clock, s: it starts at 0 (a log's start, for an imported log) and runs on across
// runs. Recordings stamp it in unsigned 64-bit nanoseconds, which end at 1.8e10 s; 1e10 s (317
// years) is past any station's clock.
inline constexpr ValueRange kClockRange_s{0.0, 1e10};

}  // namespace avk::vehicle
