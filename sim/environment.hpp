#pragma once
// The water and air around a simulated surface vehicle: a constant current and a gusting wind.
// The catamaran plant owns one and advances it with its own fixed internal step, so the gust
// sequence, and with it the whole run, depends only on the seed.

#include <cstdint>
#include <optional>
#include <random>

#include <Eigen/Core>

namespace avk::sim {

struct CatamaranParams;

// Constant and irrotational, so the plant can integrate the water-relative velocity alone.
struct CurrentConfig {
  double speed_mps = 0.0;
  double toward_deg = 0.0;  // where the water goes, clockwise from north
};

// Mean wind plus first-order Gauss–Markov gusts on its speed (the direction stays the mean one:
// the turns we simulate last seconds, wind shifts take minutes).
//
// The load on the hull is the classic cos²/sin² coefficient model, written per body axis with the
// apparent wind (air velocity relative to the hull) (u_a, v_a):
//   X = ½ ρ_air C_x A_frontal |u_a| u_a,   Y = ½ ρ_air C_y A_lateral |v_a| v_a,
//   N = x_cp · Y   (x_cp = lateral centre of pressure ahead of the centre of gravity).
// This is ½ ρ V² C(γ) A with C_X(γ) = C_x cos γ |cos γ| and C_Y(γ) = C_y sin γ |sin γ|.
struct WindConfig {
  double mean_speed_mps = 0.0;
  double from_deg = 0.0;        // where the wind comes from, clockwise from north
  double gust_sigma_mps = 0.0;  // stationary standard deviation of the gust speed
  double gust_time_constant_s = 10.0;

  double air_density_kg_m3 = 1.225;
  // Small-craft values (Blendermann's data for open boats give C_x 0.5–0.9, C_y 0.7–1.0).
  double drag_coefficient_x = 0.7;
  double drag_coefficient_y = 0.9;
  // Height of hull, deck and electronics above the waterline; with no explicit area the frontal
  // area is beam × height and the lateral area length × height.
  double windage_height_m = 0.3;
  std::optional<double> frontal_area_m2;
  std::optional<double> lateral_area_m2;
  // Masts and antennas sit forward on both vehicles, so a beam wind slowly turns the bow downwind.
  double pressure_centre_x_fraction_of_length = 0.05;
};

struct EnvironmentConfig {
  CurrentConfig current;
  WindConfig wind;
  std::uint64_t seed = 1;
};

class Environment {
 public:
  // Throws std::invalid_argument for a non-finite value, a negative speed, sigma, density, area or
  // height, or a gust time constant <= 0. The gust starts from a draw of its stationary
  // distribution so its statistics do not depend on when one starts looking.
  explicit Environment(EnvironmentConfig config);

  // Advances the gust by dt_s with the exact discretisation of the Gauss–Markov process
  // (g ← a g + σ √(1 − a²) ξ, a = e^(−dt/T)), so its variance is σ² for any dt. One normal variate
  // per call, whatever sigma is. dt_s == 0 does nothing; negative or non-finite throws.
  void advance(double dt_s);

  const EnvironmentConfig& config() const { return config_; }

  // (east, north) water velocity.
  Eigen::Vector2d current_velocity_en_mps() const;
  // Current velocity in body axes [u forward, v starboard] for a heading.
  Eigen::Vector2d current_velocity_body_mps(double heading_deg) const;

  double gust_mps() const { return gust_mps_; }
  // Mean plus gust, never negative.
  double wind_speed_mps() const;
  // (east, north) air velocity: where the air goes, opposite to from_deg.
  Eigen::Vector2d wind_velocity_en_mps() const;

  // [X N, Y N, N N·m] on a hull at heading_deg moving with ground velocity nu = [u, v, r] (body,
  // m/s and rad/s); the areas default from the vehicle's length and beam.
  Eigen::Vector3d wind_load_body(double heading_deg, const Eigen::Vector3d& nu,
                                 const CatamaranParams& params) const;

 private:
  EnvironmentConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
  double gust_mps_ = 0.0;
};

}  // namespace avk::sim
