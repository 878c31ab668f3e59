#include "sim/sensors.hpp"

#include <cmath>

#include "kinematics/angles.hpp"

namespace avk::sim {

NavSensor::NavSensor(SensorConfig config, std::uint64_t seed) : config_(config), rng_(seed) {}

void NavSensor::measure(const TruthSample& truth) {
  std::normal_distribution<double> unit(0.0, 1.0);
  // Draw every variate every time so the noise sequence does not depend on which sigmas are 0.
  const double nx = unit(rng_), ny = unit(rng_), nh = unit(rng_), nv = unit(rng_);
  vehicle::NavSample s;
  s.t_s = truth.t_s + config_.latency_s;
  s.x_m = truth.x_m + config_.gnss_sigma_m * nx;
  s.y_m = truth.y_m + config_.gnss_sigma_m * ny;
  double heading = truth.heading_deg;
  if (config_.heading_from_course_above_mps &&
      truth.speed_over_ground_mps > *config_.heading_from_course_above_mps) {
    heading = truth.course_over_ground_deg;
  }
  s.heading_deg = kinematics::wrap360_deg(heading + config_.compass_sigma_deg * nh);
  double speed = std::max(0.0, truth.speed_over_ground_mps + config_.speed_sigma_mps * nv);
  if (config_.speed_quantum_mps > 0.0) {
    speed = std::round(speed / config_.speed_quantum_mps) * config_.speed_quantum_mps;
  }
  s.speed_mps = speed;
  s.yaw_rate_dps = truth.yaw_rate_dps;
  in_flight_.push_back(s);
}

std::vector<vehicle::NavSample> NavSensor::deliver(double now_s) {
  std::vector<vehicle::NavSample> out;
  while (!in_flight_.empty() && in_flight_.front().t_s <= now_s + 1e-12) {
    out.push_back(in_flight_.front());
    in_flight_.pop_front();
  }
  return out;
}

}  // namespace avk::sim
