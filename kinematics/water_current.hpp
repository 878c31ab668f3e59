#pragma once
// A uniform current as a velocity in the local grid: where the water sets, in m/s toward east and
// toward north (not the meteorological "from"). Its own header so a turn's metadata can carry the
// current removed from it without pulling in the estimation.

namespace avk::kinematics {

struct WaterCurrent {
  double east_mps = 0.0;
  double north_mps = 0.0;
  friend bool operator==(const WaterCurrent&, const WaterCurrent&) = default;
};

}  // namespace avk::kinematics
