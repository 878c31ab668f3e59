#pragma once
// A path in time: where the vehicle is at each time, linear in between.

#include <vector>

namespace avk::kinematics {

struct TimedPoint {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  friend bool operator==(const TimedPoint&, const TimedPoint&) = default;
};
// Times non-decreasing; between two points the vehicle moves linearly in time.
using TimedPath = std::vector<TimedPoint>;

}  // namespace avk::kinematics
