#include "sim/environment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kinematics/angles.hpp"
#include "sim/catamaran.hpp"

namespace avk::sim {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Environment: " + what);
}

bool finite_nonnegative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

// Body axes [forward, starboard] of an (east, north) vector at a heading.
Eigen::Vector2d en_to_body(const Eigen::Vector2d& en, double heading_rad) {
  const double s = std::sin(heading_rad), c = std::cos(heading_rad);
  return {en.y() * c + en.x() * s, -en.y() * s + en.x() * c};
}

}  // namespace

Environment::Environment(EnvironmentConfig config) : config_(config), rng_(config.seed) {
  const CurrentConfig& c = config_.current;
  const WindConfig& w = config_.wind;
  require(finite_nonnegative(c.speed_mps) && std::isfinite(c.toward_deg),
          "current speed must be finite and >= 0, its direction finite");
  require(finite_nonnegative(w.mean_speed_mps) && std::isfinite(w.from_deg),
          "wind speed must be finite and >= 0, its direction finite");
  require(finite_nonnegative(w.gust_sigma_mps), "gust sigma must be finite and >= 0");
  require(std::isfinite(w.gust_time_constant_s) && w.gust_time_constant_s > 0.0,
          "gust time constant must be finite and > 0");
  require(finite_nonnegative(w.air_density_kg_m3) && finite_nonnegative(w.drag_coefficient_x) &&
              finite_nonnegative(w.drag_coefficient_y) && finite_nonnegative(w.windage_height_m),
          "air density, drag coefficients and windage height must be finite and >= 0");
  require(!w.frontal_area_m2 || finite_nonnegative(*w.frontal_area_m2),
          "frontal area must be finite and >= 0");
  require(!w.lateral_area_m2 || finite_nonnegative(*w.lateral_area_m2),
          "lateral area must be finite and >= 0");
  require(std::isfinite(w.pressure_centre_x_fraction_of_length),
          "pressure centre position must be finite");
  gust_mps_ = w.gust_sigma_mps * unit_(rng_);
}

void Environment::advance(double dt_s) {
  require(std::isfinite(dt_s) && dt_s >= 0.0, "dt must be finite and >= 0");
  if (dt_s == 0.0) return;
  const WindConfig& w = config_.wind;
  const double a = std::exp(-dt_s / w.gust_time_constant_s);
  gust_mps_ = a * gust_mps_ + w.gust_sigma_mps * std::sqrt(1.0 - a * a) * unit_(rng_);
}

Eigen::Vector2d Environment::current_velocity_en_mps() const {
  const double toward_rad = kinematics::deg_to_rad(config_.current.toward_deg);
  return config_.current.speed_mps * Eigen::Vector2d(std::sin(toward_rad), std::cos(toward_rad));
}

Eigen::Vector2d Environment::current_velocity_body_mps(double heading_deg) const {
  return en_to_body(current_velocity_en_mps(), kinematics::deg_to_rad(heading_deg));
}

double Environment::wind_speed_mps() const {
  return std::max(0.0, config_.wind.mean_speed_mps + gust_mps_);
}

Eigen::Vector2d Environment::wind_velocity_en_mps() const {
  const double from_rad = kinematics::deg_to_rad(config_.wind.from_deg);
  return -wind_speed_mps() * Eigen::Vector2d(std::sin(from_rad), std::cos(from_rad));
}

Eigen::Vector3d Environment::wind_load_body(double heading_deg, const Eigen::Vector3d& nu,
                                            const CatamaranParams& params) const {
  const double speed = wind_speed_mps();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  const WindConfig& w = config_.wind;
  const Eigen::Vector2d wind_body =
      en_to_body(wind_velocity_en_mps(), kinematics::deg_to_rad(heading_deg));
  const double frontal_m2 = w.frontal_area_m2.value_or(params.beam_m * w.windage_height_m);
  const double lateral_m2 = w.lateral_area_m2.value_or(params.length_m * w.windage_height_m);
  const double qx = 0.5 * w.air_density_kg_m3 * w.drag_coefficient_x * frontal_m2;
  const double qy = 0.5 * w.air_density_kg_m3 * w.drag_coefficient_y * lateral_m2;
  // The hull's damping coefficients come from whole-vehicle fits that already hold the drag of
  // still air, so the load counted here is the apparent-wind load minus the still-air load of the
  // same motion: nothing without wind, the full load on a hull at rest.
  auto sq = [](double a) { return std::abs(a) * a; };
  const double ua = wind_body.x() - nu.x(), va = wind_body.y() - nu.y();
  const double x_n = qx * (sq(ua) - sq(-nu.x()));
  const double y_n = qy * (sq(va) - sq(-nu.y()));
  const double n_nm = w.pressure_centre_x_fraction_of_length * params.length_m * y_n;
  return {x_n, y_n, n_nm};
}

}  // namespace avk::sim
