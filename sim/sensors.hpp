#pragma once
// What the navigation system reports of the true motion: GNSS position noise, compass noise,
// optionally heading from GNSS course above a speed (as the Heron's frontseat does), and a
// latency. The publication rate is the plant's scheduler tick. Seeded, so a run is repeatable.

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <vector>

#include "vehicle/vehicle.hpp"

namespace avk::sim {

struct SensorConfig {
  double gnss_sigma_m = 0.0;
  double compass_sigma_deg = 0.0;
  double speed_sigma_mps = 0.0;
  // Above this speed over ground the reported heading is the GNSS course, not the compass.
  std::optional<double> heading_from_course_above_mps;
  double latency_s = 0.0;
  // uSimMarine publishes speed rounded to 0.01 m/s; 0 leaves it unrounded.
  double speed_quantum_mps = 0.0;
};

// The truth a sensor measures.
struct TruthSample {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_over_ground_mps = 0.0;
  double course_over_ground_deg = 0.0;
  double yaw_rate_dps = 0.0;
};

class NavSensor {
 public:
  NavSensor(SensorConfig config, std::uint64_t seed);

  // Measures the truth now; the report becomes available latency_s later.
  void measure(const TruthSample& truth);
  // Reports whose latency has elapsed by now_s, oldest first; stamped with when they arrive.
  std::vector<vehicle::NavSample> deliver(double now_s);

  const SensorConfig& config() const { return config_; }

 private:
  SensorConfig config_;
  std::mt19937_64 rng_;
  std::deque<vehicle::NavSample> in_flight_;
};

}  // namespace avk::sim
