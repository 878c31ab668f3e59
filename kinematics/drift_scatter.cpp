#include "kinematics/drift_scatter.hpp"

#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::kinematics {

std::optional<DriftScatter> drift_scatter_of(const std::vector<SteadyLeg>& legs,
                                             const std::optional<WaterCurrent>& c,
                                             SpeedReference ref) {
  const WaterCurrent current = c.value_or(WaterCurrent{});
  double along = 0.0, cross = 0.0, duration = 0.0;
  std::size_t n = 0;
  for (const SteadyLeg& leg : legs) {
    if (!(leg.water_speed_mps > 0.0)) continue;
    const auto v = ground_velocity_mps(leg);
    const auto p = ground_velocity_for(leg.heading_deg, leg.water_speed_mps, current, ref);
    const double h = deg_to_rad(leg.heading_deg);
    const double de = v[0] - p[0], dn = v[1] - p[1];
    const double a = de * std::sin(h) + dn * std::cos(h);
    const double x = de * std::cos(h) - dn * std::sin(h);  // to starboard
    along += a * a;
    cross += x * x;
    duration += leg.t_s.back() - leg.t_s.front();
    ++n;
  }
  if (n < kMinDriftScatterLegs) return std::nullopt;
  const auto m = static_cast<double>(n);
  return DriftScatter{std::sqrt(along / m), std::sqrt(cross / m), n, duration / m};
}

std::optional<DriftScatter> pooled(const std::vector<DriftScatter>& parts) {
  double along = 0.0, cross = 0.0, duration = 0.0;
  std::size_t n = 0;
  for (const DriftScatter& d : parts) {
    const auto w = static_cast<double>(d.legs);
    along += w * d.along_mps * d.along_mps;
    cross += w * d.cross_mps * d.cross_mps;
    duration += w * d.mean_leg_s;
    n += d.legs;
  }
  if (n == 0) return std::nullopt;
  const auto m = static_cast<double>(n);
  return DriftScatter{std::sqrt(along / m), std::sqrt(cross / m), n, duration / m};
}

}  // namespace avk::kinematics
