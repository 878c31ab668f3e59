#pragma once
// Rudder/thrust to left/right thrust for differential-drive vehicles (the Kingfisher M200), as the
// M200 MOOS driver of the thesis' time mixed them. The turns the CKT learns from the M200 were
// shaped by this mixing, so it is reproduced as it was rather than improved.

namespace avk::vehicle {

struct MixConfig {
  // The rudder's share of the differential: bounds how hard a turn may brake one side.
  double max_rudder_mix_pct = 50.0;
  // Full scale of each side; both outputs stay within ±max_thrust_pct.
  double max_thrust_pct = 100.0;
};

struct DifferentialThrust {
  double left_pct = 0;
  double right_pct = 0;
};

// L = thrust + rudder, R = thrust − rudder (rudder clamped to ±max_rudder_mix, thrust to ±100),
// scaled to max_thrust. When one side saturates, the excess is taken off the other side, so a hard
// turn at full thrust keeps its left/right difference instead of flattening into straight ahead.
// Positive rudder (starboard) gives left > right.
DifferentialThrust mix_differential(double rudder_pct, double thrust_pct, const MixConfig& c = {});

}  // namespace avk::vehicle
