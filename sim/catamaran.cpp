#include "sim/catamaran.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "kinematics/angles.hpp"

namespace avk::sim {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("CatamaranPlant: " + what);
}

bool finite_nonnegative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

bool finite_nonpositive(double v) {
  return std::isfinite(v) && v <= 0.0;
}

double signed_square(double a) {
  return std::abs(a) * a;
}

constexpr double kGravity_mps2 = 9.81;

// The M200's three calibrated numbers (docs/sim-config.md): the hull-lift yaw damping per m/s of
// speed, the impeller spin-up lag and the reversing bucket's share of ahead thrust.
constexpr double kM200YawDampingPerSpeed = -14.0;
constexpr double kM200JetLag_s = 0.3;
constexpr double kM200JetReverseFraction = 0.35;

// A call's time is split into whole grid steps with this tolerance (in steps), so that sums such
// as 40 × 0.25 s, which land a few ulps short of a grid point, still take the step.
constexpr double kGridTolerance = 1e-7;

void validate(const CatamaranParams& p) {
  require(std::isfinite(p.length_m) && p.length_m > 0.0 && finite_nonnegative(p.beam_m) &&
              finite_nonnegative(p.max_speed_mps),
          "length must be finite and > 0, beam and max speed finite and >= 0");
  require(p.mass.allFinite(), "mass matrix must be finite");
  require(p.mass(0, 1) == 0.0 && p.mass(0, 2) == 0.0 && p.mass(1, 0) == 0.0 && p.mass(2, 0) == 0.0,
          "mass matrix must not couple surge with sway or yaw");
  const Eigen::Matrix3d symmetric = 0.5 * (p.mass + p.mass.transpose());
  require(symmetric.llt().info() == Eigen::Success, "mass matrix must be positive definite");
  require(finite_nonpositive(p.xu) && finite_nonpositive(p.yv) && finite_nonpositive(p.nr) &&
              finite_nonpositive(p.xuu) && finite_nonpositive(p.yvv) && finite_nonpositive(p.nrr) &&
              finite_nonpositive(p.nr_per_speed) && finite_nonnegative(p.yaw_damping_rate_gain),
          "damping coefficients must be finite and <= 0, the yaw rate gain >= 0");
  require(finite_nonnegative(p.thruster_y_m) && std::isfinite(p.thruster_x_m),
          "thruster position must be finite, its lateral offset >= 0");
  require(std::isfinite(p.lag_s) && p.lag_s > 0.0, "thruster lag must be finite and > 0");
  require(finite_nonnegative(p.max_forward_thrust_n) &&
              finite_nonnegative(p.max_reverse_thrust_n) && finite_nonnegative(p.prop_k_pos) &&
              finite_nonnegative(p.prop_k_neg) && finite_nonnegative(p.n_max_rps) &&
              finite_nonpositive(p.n_min_rps),
          "thrust map values must be finite, >= 0 (n_min <= 0)");
  require(std::isfinite(p.jet_reverse_fraction) && p.jet_reverse_fraction >= 0.0 &&
              p.jet_reverse_fraction <= 1.0,
          "jet reverse fraction must be in [0, 1]");
  require(p.thruster != ThrusterKind::waterjet || p.n_max_rps > 0.0,
          "a waterjet needs an impeller speed n_max > 0");
  require(finite_nonnegative(p.cross_flow_cd) && finite_nonnegative(p.draught_m) &&
              finite_nonnegative(p.water_density_kg_m3) && p.cross_flow_strips >= 1,
          "cross-flow drag values must be finite and >= 0, with at least one strip");
  require(std::isfinite(p.internal_step_s) && p.internal_step_s > 0.0,
          "internal step must be finite and > 0");
}

}  // namespace

CatamaranParams CatamaranParams::m200() {
  CatamaranParams p;
  p.name = "m200";
  // Clearpath Kingfisher M200, the thesis' boat (§3.4.2): two waterjets, differential drive.
  // Published: length 1.35 m, beam 0.98 m, about 29 kg, top speed about 2 m/s. The Heron that
  // followed it has the same hull (1.35 m × 0.98 m, 28 kg), so the hull's resistance, sway damping
  // and geometry come from the Heron's description; the propulsion and the yaw damping at speed
  // are the M200's own. docs/sim-config.md gives the argument for each number.
  p.length_m = 1.35;
  p.beam_m = 0.98;
  p.thruster_x_m = -0.53;
  p.thruster_y_m = 0.378;  // the jets sit on the hull centrelines
  constexpr double kMass_kg = 29.0;
  // The mass sits in the two hulls: I = m (L²/12 + y_hull²) ≈ 8.6 kg·m². Added inertia: strip
  // theory (ρπT²/2 per metre of a plate-like section) gives ≈ 9.5 kg·m² over both hulls; the
  // rounded, semi-planing pontoons have less, so half of it is taken.
  const double izz_kgm2 =
      kMass_kg * (p.length_m * p.length_m / 12.0 + p.thruster_y_m * p.thruster_y_m);
  // Surge and sway added mass as the Heron's (5 %), and equal for the same reason: without hull
  // lift in sway (N_v) an unbalanced Munk moment (m22 − m11) u v would dominate the turn.
  p.mass = Eigen::Vector3d(kMass_kg * 1.05, kMass_kg * 1.05, izz_kgm2 + 0.5 * 9.5).asDiagonal();
  p.xu = -16.45;
  p.yv = -15.80;
  p.xuu = -2.94;
  p.yvv = -2.76;
  // At rest the yaw damping is the Heron hull's; at speed the two hulls add their lift moment.
  p.nr = -6.0;
  p.nrr = -5.0;
  p.nr_per_speed = kM200YawDampingPerSpeed;
  p.cross_flow_drag = true;
  p.draught_m = 0.12;
  p.thruster = ThrusterKind::waterjet;
  p.lag_s = kM200JetLag_s;
  p.n_max_rps = 628.0;  // 6000 rpm, a nominal impeller speed: only the n² shape matters
  // Ahead thrust per jet from the published top speed: 2 T = −X_u U − X_uu U² at U = 2 m/s.
  constexpr double kTopSpeed_mps = 2.0;
  p.max_forward_thrust_n = 0.5 * (-p.xu * kTopSpeed_mps - p.xuu * kTopSpeed_mps * kTopSpeed_mps);
  p.jet_reverse_fraction = kM200JetReverseFraction;
  // Operated 10 % below the top speed, as the Otter is.
  p.max_speed_mps = 0.9 * kTopSpeed_mps;
  return p;
}

CatamaranParams CatamaranParams::heron() {
  CatamaranParams p;
  p.name = "heron";
  // Clearpath Heron, from its Gazebo simulation description (heron_gazebo): propellers.
  p.length_m = 1.35;
  p.beam_m = 0.98;
  p.max_speed_mps = 1.7;
  // Rigid body 28 kg, Izz 10 kg·m². The description has no added mass, so a modest amount is
  // added: 5 % of the mass in surge and in sway, 20 % of the inertia in yaw. Sway is kept equal to
  // surge on purpose: m22 > m11 brings the Munk moment (m22 − m11) u v, which in a real hull is
  // partly offset by hull lift (N_v, Y_r) that this description lacks, and the damping here
  // was tuned without it. With 50 % in sway the unbalanced moment would nearly triple the steady
  // yaw rate at (60 %, 40 %) (19 → 44 deg/s, radius 4.5 → 1.2 m).
  p.mass = Eigen::Vector3d(28.0 * 1.05, 28.0 * 1.05, 10.0 * 1.2).asDiagonal();
  p.xu = -16.45;
  p.yv = -15.80;
  p.nr = -6.0;
  p.xuu = -2.94;
  p.yvv = -2.76;
  p.nrr = -5.0;
  p.thruster_x_m = -0.53;
  p.thruster_y_m = 0.378;
  p.lag_s = 0.05;
  p.thruster = ThrusterKind::thrust;
  p.max_forward_thrust_n = 33.6;
  p.max_reverse_thrust_n = 19.88;
  p.cross_flow_drag = true;  // hulls moving sideways in a turn: strip theory over each pontoon
  p.draught_m = 0.12;
  return p;
}

CatamaranParams CatamaranParams::otter() {
  CatamaranParams p;
  p.name = "otter";
  // Maritime Robotics Otter as in Fossen's MSS / Python Vehicle Simulator (otter.py): 55 kg hull
  // plus 25 kg payload, 3-DOF mass matrix including added mass.
  p.length_m = 2.0;
  p.beam_m = 1.08;
  p.mass << 85.5, 0.0, 0.0,  //
      0.0, 162.5, 12.25,     //
      0.0, 12.25, 42.65;
  // Linear damping only, from time constants there; yaw damping grows as N_r (1 + 10|r|).
  p.xu = -77.55;
  p.yv = -162.5;
  p.nr = -42.65;
  p.yaw_damping_rate_gain = 10.0;
  // The model places the propellers laterally only; the transom is assumed for x.
  p.thruster_x_m = -1.0;
  p.thruster_y_m = 0.395;
  p.lag_s = 0.1;
  p.thruster = ThrusterKind::shaft_speed;
  p.prop_k_pos = 0.01108;
  p.prop_k_neg = 0.006445;
  // Shaft speeds at which each propeller gives half the rated 24.4 kgf ahead and 13.6 kgf astern.
  p.n_max_rps = std::sqrt(0.5 * 24.4 * kGravity_mps2 / p.prop_k_pos);   // ≈ 103.9
  p.n_min_rps = -std::sqrt(0.5 * 13.6 * kGravity_mps2 / p.prop_k_neg);  // ≈ −101.7
  p.cross_flow_drag = true;
  p.cross_flow_cd = 1.0;
  p.draught_m = 0.195;
  p.cross_flow_strips = 20;
  p.water_density_kg_m3 = 1025.0;
  // The model's full-thrust speed is its 6 kn design speed; operate 10 % below it.
  p.max_speed_mps = 0.9 * p.steady_surge_speed_mps(100.0);  // ≈ 2.78
  return p;
}

std::optional<CatamaranParams> CatamaranParams::by_name(std::string_view name) {
  if (name == "m200") return m200();
  if (name == "heron") return heron();
  if (name == "otter") return otter();
  return std::nullopt;
}

std::optional<CatamaranParams> CatamaranParams::for_kind(vehicle::VehicleKind kind) {
  switch (kind) {
    case vehicle::VehicleKind::catamaran_m200:
      return m200();
    case vehicle::VehicleKind::catamaran_heron:
      return heron();
    case vehicle::VehicleKind::catamaran_otter:
      return otter();
    case vehicle::VehicleKind::usim:
    case vehicle::VehicleKind::m200:
      break;
  }
  return std::nullopt;
}

double CatamaranParams::actuator_target(double pct) const {
  const double f = std::clamp(pct, -100.0, 100.0) / 100.0;
  if (thruster == ThrusterKind::thrust) {
    return f >= 0.0 ? f * max_forward_thrust_n : f * max_reverse_thrust_n;
  }
  if (thruster == ThrusterKind::waterjet) return f * n_max_rps;
  return f >= 0.0 ? f * n_max_rps : -f * n_min_rps;
}

double CatamaranParams::thrust_from_actuator_n(double actuator) const {
  if (thruster == ThrusterKind::thrust) return actuator;
  if (thruster == ThrusterKind::waterjet) {
    const double ahead_n = max_forward_thrust_n * (actuator / n_max_rps) * (actuator / n_max_rps);
    return actuator >= 0.0 ? ahead_n : -jet_reverse_fraction * ahead_n;
  }
  return (actuator >= 0.0 ? prop_k_pos : prop_k_neg) * signed_square(actuator);
}

double CatamaranParams::steady_surge_speed_mps(double pct) const {
  const double thrust = 2.0 * thrust_n(pct);
  // Root of −X_uu u² − X_u u = |T| in the form that stays exact when X_uu is 0.
  const double a = -xuu, b = -xu;
  const double t = std::abs(thrust);
  if (t == 0.0) return 0.0;
  const double u = 2.0 * t / (b + std::sqrt(b * b + 4.0 * a * t));
  return thrust >= 0.0 ? u : -u;
}

CatamaranPlant::CatamaranPlant(CatamaranParams p, EnvironmentConfig env, CatamaranState initial)
    : params_(std::move(p)), env_(env) {
  validate(params_);
  require(std::isfinite(initial.x_m) && std::isfinite(initial.y_m) &&
              std::isfinite(initial.heading_deg) && std::isfinite(initial.u_mps) &&
              std::isfinite(initial.v_mps) && std::isfinite(initial.r_rps) &&
              std::isfinite(initial.left_actuator) && std::isfinite(initial.right_actuator),
          "initial state must be finite");
  mass_inverse_ = params_.mass.inverse();
  const double heading_deg = kinematics::wrap360_deg(initial.heading_deg);
  // The initial velocity is over ground; the plant integrates it through the water.
  const Eigen::Vector2d current_body = env_.current_velocity_body_mps(heading_deg);
  grid_ << initial.x_m, initial.y_m, kinematics::deg_to_rad(heading_deg),
      initial.u_mps - current_body.x(), initial.v_mps - current_body.y(), initial.r_rps,
      initial.left_actuator, initial.right_actuator;
  now_ = grid_;
  publish(now_);
}

CatamaranPlant::Vector8d CatamaranPlant::derivative(const Vector8d& s, double left_target,
                                                    double right_target) const {
  const CatamaranParams& p = params_;
  const double psi = s(2), ur = s(3), vr = s(4), r = s(5);
  const double sin_psi = std::sin(psi), cos_psi = std::cos(psi);
  const Eigen::Vector2d current_en = env_.current_velocity_en_mps();

  Vector8d d;
  d(0) = ur * sin_psi + vr * cos_psi + current_en.x();
  d(1) = ur * cos_psi - vr * sin_psi + current_en.y();
  d(2) = r;

  const double left_n = p.thrust_from_actuator_n(s(6));
  const double right_n = p.thrust_from_actuator_n(s(7));
  // The left thruster sits to port (y = −l), so pushing harder there turns the bow to starboard.
  Eigen::Vector3d force(left_n + right_n, 0.0, (left_n - right_n) * p.thruster_y_m);

  force += Eigen::Vector3d(
      p.xu * ur + p.xuu * signed_square(ur), p.yv * vr + p.yvv * signed_square(vr),
      (p.nr + p.nr_per_speed * std::abs(ur)) * (1.0 + p.yaw_damping_rate_gain * std::abs(r)) * r +
          p.nrr * signed_square(r));

  const double m11 = p.mass(0, 0), m22 = p.mass(1, 1);
  const double m23 = 0.5 * (p.mass(1, 2) + p.mass(2, 1));
  // With ν_r the rigid-body u·v terms cancel and what is left of the last row is the added-mass
  // Munk moment (m22 − m11) u_r v_r, which is what turns an oblique hull broadside.
  force -= Eigen::Vector3d(-(m22 * vr + m23 * r) * r, m11 * ur * r,
                           (m22 * vr + m23 * r) * ur - m11 * ur * vr);

  if (p.cross_flow_drag) {
    const double dx = p.length_m / p.cross_flow_strips;
    const double k = 0.5 * p.water_density_kg_m3 * p.draught_m * p.cross_flow_cd * dx;
    double y_n = 0.0, n_nm = 0.0;
    for (int i = 0; i < p.cross_flow_strips; ++i) {
      const double x = -0.5 * p.length_m + (i + 0.5) * dx;
      const double f = -k * signed_square(vr + x * r);
      y_n += f;
      n_nm += x * f;
    }
    force.y() += y_n;
    force.z() += n_nm;
  }

  if (env_.wind_speed_mps() > 0.0) {
    const Eigen::Vector2d current_body(current_en.y() * cos_psi + current_en.x() * sin_psi,
                                       -current_en.y() * sin_psi + current_en.x() * cos_psi);
    const Eigen::Vector3d nu(ur + current_body.x(), vr + current_body.y(), r);
    force += env_.wind_load_body(kinematics::rad_to_deg(psi), nu, p);
  }

  d.segment<3>(3) = mass_inverse_ * force;
  d(6) = (left_target - s(6)) / p.lag_s;
  d(7) = (right_target - s(7)) / p.lag_s;
  return d;
}

CatamaranPlant::Vector8d CatamaranPlant::rk4(const Vector8d& s, double h, double left_target,
                                             double right_target) const {
  const Vector8d k1 = derivative(s, left_target, right_target);
  const Vector8d k2 = derivative(s + 0.5 * h * k1, left_target, right_target);
  const Vector8d k3 = derivative(s + 0.5 * h * k2, left_target, right_target);
  const Vector8d k4 = derivative(s + h * k3, left_target, right_target);
  return s + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

void CatamaranPlant::advance(double dt_s, double left_pct, double right_pct) {
  require(std::isfinite(dt_s) && dt_s >= 0.0, "dt must be finite and >= 0");
  require(std::isfinite(left_pct) && std::isfinite(right_pct), "commands must be finite");
  const double h = params_.internal_step_s;
  const double left_target = params_.actuator_target(left_pct);
  const double right_target = params_.actuator_target(right_pct);

  // The remainder is kept apart from the step count, so it stays within a step of 0 and exact to
  // far below a nanosecond however long the run.
  remainder_s_ += dt_s;
  const auto steps = static_cast<long long>(std::floor(remainder_s_ / h + kGridTolerance));
  for (long long i = 0; i < steps; ++i) {
    grid_ = rk4(grid_, h, left_target, right_target);
    env_.advance(h);
  }
  grid_steps_ += steps;
  remainder_s_ -= static_cast<double>(steps) * h;
  // Within the tolerance above of the grid point: that is the grid point.
  if (std::abs(remainder_s_) < kGridTolerance * h) remainder_s_ = 0.0;
  now_ = remainder_s_ > 0.0 ? rk4(grid_, remainder_s_, left_target, right_target) : grid_;
  publish(now_);
}

void CatamaranPlant::publish(const Vector8d& s) {
  const Eigen::Vector2d current_body = env_.current_velocity_body_mps(kinematics::rad_to_deg(s(2)));
  state_.x_m = s(0);
  state_.y_m = s(1);
  state_.heading_deg = kinematics::wrap360_deg(kinematics::rad_to_deg(s(2)));
  state_.u_mps = s(3) + current_body.x();
  state_.v_mps = s(4) + current_body.y();
  state_.r_rps = s(5);
  state_.left_actuator = s(6);
  state_.right_actuator = s(7);
}

double CatamaranPlant::time_s() const {
  return static_cast<double>(grid_steps_) * params_.internal_step_s + remainder_s_;
}

double CatamaranPlant::speed_over_ground_mps() const {
  return std::hypot(state_.u_mps, state_.v_mps);
}

double CatamaranPlant::course_over_ground_deg() const {
  if (state_.u_mps == 0.0 && state_.v_mps == 0.0) return state_.heading_deg;
  return kinematics::wrap360_deg(state_.heading_deg +
                                 kinematics::rad_to_deg(std::atan2(state_.v_mps, state_.u_mps)));
}

double CatamaranPlant::yaw_rate_dps() const {
  return kinematics::rad_to_deg(state_.r_rps);
}

Eigen::Vector3d CatamaranPlant::water_relative_velocity() const {
  return now_.segment<3>(3);
}

double CatamaranPlant::left_thrust_n() const {
  return params_.thrust_from_actuator_n(now_(6));
}

double CatamaranPlant::right_thrust_n() const {
  return params_.thrust_from_actuator_n(now_(7));
}

TruthSample CatamaranPlant::truth() const {
  TruthSample t;
  t.t_s = time_s();
  t.x_m = state_.x_m;
  t.y_m = state_.y_m;
  t.heading_deg = state_.heading_deg;
  t.speed_over_ground_mps = speed_over_ground_mps();
  t.course_over_ground_deg = course_over_ground_deg();
  t.yaw_rate_dps = yaw_rate_dps();
  return t;
}

}  // namespace avk::sim
