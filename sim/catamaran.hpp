#pragma once
// A twin-hull, differential-thrust surface vehicle in Fossen's 3-DOF form (surge, sway, yaw):
//   M ν̇_r + C(ν_r) ν_r + D(ν_r) ν_r = τ + τ_wind,   ν = ν_r + ν_c,
// with ν = [u forward, v starboard, r clockwise] in body axes and ν_c the current in body axes.
// For a constant irrotational current this relative-velocity form is exact (the rigid-body
// Coriolis terms of ν and ν_r differ by exactly M_RB ν̇_c), so the plant integrates ν_r and the
// position moves with R(ψ) ν_r plus the current.
//
// Unlike UsimPlant this is a physical model: it is the simulator the M200's real turns are
// compared with, and the one that can carry wind and current.

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "sim/environment.hpp"
#include "sim/sensors.hpp"
#include "vehicle/vehicle_kind.hpp"

namespace avk::sim {

// What a thruster's first-order lag acts on, and so what the actuator state holds.
enum class ThrusterKind {
  // The lag acts on thrust (N); the command maps linearly to thrust on each side of 0.
  thrust,
  // The lag acts on shaft speed n (rad/s); the command maps linearly to n on each side of 0 and
  // thrust is k n|n| (k_pos forward, k_neg astern), as for a fixed-pitch propeller.
  shaft_speed,
  // A waterjet: the lag acts on the impeller speed n (rad/s), the command maps linearly to n on
  // each side of 0 (n_max_rps at ±100 %) and thrust goes as n² (max_forward_thrust_n at n_max).
  // Astern the impeller still turns ahead and a reversing bucket turns the jet round, which wastes
  // most of it: thrust is −jet_reverse_fraction × the ahead thrust at that impeller speed. The
  // sign of the state stands for the bucket's position (a simplification: a real bucket moves
  // while the impeller keeps turning, here the jet passes through zero).
  waterjet,
};

struct CatamaranParams {
  std::string name;
  double length_m = 0.0;
  double beam_m = 0.0;
  double max_speed_mps = 0.0;  // rated operating speed, for guidance; not a limit of the model
  // Rigid-body plus added mass, [[m11, 0, 0], [0, m22, m23], [0, m32, m33]] (kg, kg·m, kg·m²).
  Eigen::Matrix3d mass = Eigen::Matrix3d::Identity();
  // Damping: −[X_u u + X_uu |u|u, Y_v v + Y_vv |v|v, (N_r + N_ru |u|)(1 + g|r|) r + N_rr |r|r],
  // all <= 0 (N_ru is nr_per_speed below).
  double xu = 0.0, yv = 0.0, nr = 0.0;     // N·s/m, N·s/m, N·m·s
  double xuu = 0.0, yvv = 0.0, nrr = 0.0;  // N·s²/m², N·s²/m², N·m·s²
  double yaw_damping_rate_gain = 0.0;      // g above (s/rad): the Otter's 10
  // Linear yaw damping that grows with speed through the water: N_r += nr_per_speed × |u_r|
  // (N·m·s per m/s, <= 0). Slender hulls yawing at speed work as low-aspect-ratio wings, so their
  // lift moment, and with it the yaw damping, is proportional to u (Clarke et al. 1983).
  double nr_per_speed = 0.0;
  // Thrusters at (thruster_x_m, ±thruster_y_m), pushing along body x; x does not enter 3-DOF.
  double thruster_y_m = 0.0;
  double thruster_x_m = 0.0;
  double lag_s = 0.1;
  ThrusterKind thruster = ThrusterKind::thrust;
  // ThrusterKind::thrust: thrust at +100 % and magnitude at −100 %; ThrusterKind::waterjet:
  // thrust at n_max_rps (max_reverse_thrust_n is not used).
  double max_forward_thrust_n = 0.0;
  double max_reverse_thrust_n = 0.0;
  // ThrusterKind::waterjet: astern thrust as a fraction of ahead thrust at the same impeller speed.
  double jet_reverse_fraction = 0.0;
  // ThrusterKind::shaft_speed: k in N·s²/rad², shaft speed at +100 % and at −100 % (negative);
  // ThrusterKind::waterjet: n_max_rps only (rad/s).
  double prop_k_pos = 0.0;
  double prop_k_neg = 0.0;
  double n_max_rps = 0.0;
  double n_min_rps = 0.0;
  // Strip-theory cross-flow drag over one hull: Y = −∫ ½ ρ T C_d |v + x r|(v + x r) dx and
  // N = −∫ x (…) dx over x ∈ [−L/2, L/2], midpoint rule.
  bool cross_flow_drag = false;
  double cross_flow_cd = 1.0;
  double draught_m = 0.0;
  int cross_flow_strips = 20;
  double water_density_kg_m3 = 1025.0;
  double internal_step_s = 0.01;

  // The Kingfisher M200 of the thesis: twin waterjets (docs/sim-config.md says where each number
  // comes from).
  static CatamaranParams m200();
  // A propeller-driven Clearpath Heron, from its Gazebo description (heron_gazebo): what m200()
  // was before the M200 got its waterjets.
  static CatamaranParams heron();
  static CatamaranParams otter();
  // "m200", "heron" or "otter"; nullopt for anything else.
  static std::optional<CatamaranParams> by_name(std::string_view name);
  // The hull a simulated catamaran kind stands for; nullopt for the other kinds.
  static std::optional<CatamaranParams> for_kind(vehicle::VehicleKind kind);

  // Actuator state (thrust N, shaft or impeller speed rad/s) a command settles to; pct clamped to
  // ±100.
  double actuator_target(double pct) const;
  // Thrust (N) of one thruster at an actuator state.
  double thrust_from_actuator_n(double actuator) const;
  // Steady thrust of one thruster for a command.
  double thrust_n(double pct) const { return thrust_from_actuator_n(actuator_target(pct)); }
  // Steady straight-line speed through the water with both thrusters at pct (surge balance
  // X_u u + X_uu |u|u + 2 T = 0).
  double steady_surge_speed_mps(double pct) const;
};

struct CatamaranState {
  double x_m = 0.0, y_m = 0.0, heading_deg = 0.0;  // heading in [0, 360)
  // Velocity over ground in body axes (m/s) and yaw rate (rad/s, + to starboard).
  double u_mps = 0.0, v_mps = 0.0, r_rps = 0.0;
  // Lagged thrust (N), shaft speed or impeller speed (rad/s), see ThrusterKind.
  double left_actuator = 0.0, right_actuator = 0.0;
};

class CatamaranPlant {
 public:
  // Throws std::invalid_argument for parameters or an initial state that are not finite, a mass
  // matrix that is not symmetric positive definite, positive damping coefficients, a lag or
  // internal step <= 0, or an invalid environment (see Environment).
  CatamaranPlant(CatamaranParams p, EnvironmentConfig env, CatamaranState initial = {});

  // Advances dt_s seconds holding the commands (percent, clamped to ±100). The dynamics run with
  // classical RK4 on a fixed grid of internal_step_s from t = 0, whatever dt_s is: the grid steps
  // that fall within dt_s are taken with this call's commands, and the state reported afterwards
  // is the last grid state carried over the remainder by one partial RK4 step that is not kept.
  // So the trajectory on the grid does not depend on how the time was cut into calls, and state()
  // is still the state at time_s(). The wind gust advances once per grid step.
  // dt_s == 0 only re-evaluates the reported state; negative or non-finite dt_s, or a non-finite
  // command, throws std::invalid_argument.
  void advance(double dt_s, double left_pct, double right_pct);

  const CatamaranState& state() const { return state_; }
  const CatamaranParams& params() const { return params_; }
  const Environment& environment() const { return env_; }
  double time_s() const;

  double speed_over_ground_mps() const;
  // Direction of travel over ground; the heading when not moving.
  double course_over_ground_deg() const;
  double yaw_rate_dps() const;
  // What a navigation sensor measures now, stamped with time_s().
  TruthSample truth() const;
  // [u_r, v_r, r]: velocity through the water in body axes.
  Eigen::Vector3d water_relative_velocity() const;
  double left_thrust_n() const;
  double right_thrust_n() const;

  // Integration state: x, y (m), unwrapped heading (rad), u_r, v_r (m/s), r (rad/s), left and
  // right actuator.
  using Vector8d = Eigen::Matrix<double, 8, 1>;

 private:
  Vector8d derivative(const Vector8d& s, double left_target, double right_target) const;
  Vector8d rk4(const Vector8d& s, double h, double left_target, double right_target) const;
  void publish(const Vector8d& s);

  CatamaranParams params_;
  Environment env_;
  Eigen::Matrix3d mass_inverse_;
  Vector8d grid_;  // state at grid_steps_ × internal_step_s
  Vector8d now_;   // state at time_s()
  long long grid_steps_ = 0;
  double remainder_s_ = 0.0;  // time_s() − grid time, in [0, internal_step_s)
  CatamaranState state_;
};

}  // namespace avk::sim
