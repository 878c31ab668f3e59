#pragma once
// The black-box yaw model (thesis §3.4.1, eq. 3.5): controller, actuators and hull identified
// together from desired and measured headings, so a prediction needs neither the controller design
// nor actuator positions.
//
//   thesis form:     psi(k+1)          = sum_i a_i e(k-i) + sum_i b_i psi(k-i)
//   invariant form:  psi(k+1) - psi(k) = sum_i a_i e(k-i) + sum_i c_i (psi(k-i) - psi(k-i-1))
//
// e is the wrapped heading error (desired - measured). The thesis form on absolute headings
// predicts differently for the same turn started on different courses unless the b sum to one;
// the invariant form sees only errors and heading increments, so it cannot (§3.4.3 future work).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/resample.hpp"

namespace avk::kinematics {

enum class YawModelForm { thesis, invariant };
const char* to_string(YawModelForm f);
std::optional<YawModelForm> yaw_model_form_from_string(const std::string& s);

// Speed through a turn: u(k+1) = u(k) + gain (u_desired - u(k)) - sag |psi(k) - psi(k-1)| + bias.
struct SpeedModel {
  double gain = 0.0;
  double sag_per_deg = 0.0;
  double bias_mps = 0.0;
};

struct YawModel {
  YawModelForm form = YawModelForm::invariant;
  std::size_t history = 40;  // n: samples of error and heading (or increment) history
  double rate_hz = 4.0;
  std::vector<double> error_coeffs;    // a_0..a_{n-1}: a_0 multiplies the newest error
  std::vector<double> heading_coeffs;  // b (thesis) or c (invariant), newest first
  double ridge_lambda = 0.0;
  bool refined = false;
  std::optional<SpeedModel> speed;

  double dt_s() const { return 1.0 / rate_hz; }
  std::size_t coefficient_count() const { return error_coeffs.size() + heading_coeffs.size(); }
  // Samples a prediction needs before its first step: n (thesis) or n + 1 (increments).
  std::size_t warmup() const { return form == YawModelForm::thesis ? history : history + 1; }
};

// The state a prediction starts from: the last warmup() headings and desired headings, oldest
// first, unwrapped (as in IdentSegment), and the pose and speed now.
struct YawHistory {
  std::vector<double> heading_deg;
  std::vector<double> desired_heading_deg;
};

// A steady course: heading and desired heading equal to course for the whole history.
YawHistory steady_history(const YawModel& m, double course_deg);
// A steady turn at yaw_rate_dps (+ clockwise) ending on course_deg: the headings step by
// yaw_rate x dt and the desired heading leads them by the constant error under which the model
// holds that rate, so a prediction from it starts turning at yaw_rate_dps. Throws
// std::invalid_argument for a model whose error coefficients sum to zero (it cannot hold a rate).
YawHistory turning_history(const YawModel& m, double course_deg, double yaw_rate_dps);
// The history ending at sample k of a segment (k >= warmup() - 1).
YawHistory history_at(const YawModel& m, const IdentSegment& s, std::size_t k);

struct PredictedStep {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;  // unwrapped
  double speed_mps = 0.0;
};

struct PredictOptions {
  std::size_t steps = 120;  // 30 s at 4 Hz
  // Stop once the heading is within this of the goal (the mission's completion rule); 0 = never.
  double completion_threshold_deg = 0.0;
  bool use_speed_model = false;
  double desired_speed_mps = 0.0;  // for the speed model; 0 = hold the start speed
};

// Thesis §3.4.1's listing: from the history, with the desired heading held at `desired_deg`
// (unwrapped, near the history's headings), step the position with the current heading and
// speed, predict the next heading, update the error and heading vectors. The first point is the
// start pose.
std::vector<PredictedStep> predict(const YawModel& m, const YawHistory& history, double desired_deg,
                                   Pose start, double speed_mps,
                                   const PredictOptions& options = {});

// A normalised right turn of dheading_deg from a steady course (start at the origin heading north
// for the invariant form; the thesis form starts on `course_deg` and is rotated back to north,
// which is where its lack of invariance shows).
// With use_speed_model (and a model that has one) the speed follows the speed model towards
// speed_mps instead of staying constant. A nonzero initial_yaw_rate_dps (+ into the turn, -
// against it) starts the model turning at that rate (turning_history) instead of on a steady
// course. speed_after_mps: the turn starts at speed_mps and the speed model
// follows the commanded speed stepping to this with the new heading (it needs use_speed_model;
// without it the speed stays at speed_mps).
Polyline predict_normalized_turn(const YawModel& m, double speed_mps, double dheading_deg,
                                 double completion_threshold_deg, double course_deg = 0.0,
                                 std::size_t max_steps = 400, bool use_speed_model = false,
                                 double initial_yaw_rate_dps = 0.0,
                                 std::optional<double> speed_after_mps = std::nullopt);

// --- identification ---------------------------------------------------------------------

struct FitOptions {
  YawModelForm form = YawModelForm::invariant;
  std::size_t history = 40;
  // Ridge strength; empty: choose from a grid by validation trajectory error (needs validation
  // segments; 0 without them).
  std::optional<double> ridge_lambda = 0.0;
};

// Linear least squares (column-pivoted Householder QR on the stacked regressors; ridge by
// augmenting with sqrt(lambda) I, never the normal equations). Regressor windows never span
// segments. Throws std::invalid_argument with fewer equations than coefficients.
YawModel fit_yaw_model(const std::vector<IdentSegment>& training, const FitOptions& options,
                       const std::vector<IdentSegment>& validation = {});

// Identifies the speed model on the same data (needs desired speed); empty without it.
std::optional<SpeedModel> fit_speed_model(const std::vector<IdentSegment>& segments);

// A stretch of data that starts where the desired heading steps, for trajectory-level errors.
struct TurnWindow {
  const IdentSegment* segment = nullptr;
  std::size_t start = 0;   // the sample at which the desired heading has changed
  std::size_t length = 0;  // samples predicted (until the next step or the window limit)
  double step_deg = 0.0;   // the desired-heading change
};
std::vector<TurnWindow> turn_windows(const std::vector<IdentSegment>& segments, std::size_t warmup,
                                     double min_step_deg = 5.0, double max_length_s = 30.0);

struct TrajectoryError {
  double position_mse_m2 = 0.0;  // per predicted point vs the measured point at the same time
  double heading_rms_deg = 0.0;
  std::size_t windows = 0;
};
// Simulation error over the windows (constant speed from the window start, or the speed model).
TrajectoryError trajectory_error(const YawModel& m, const std::vector<TurnWindow>& windows,
                                 bool use_speed_model = false);
// One-step-ahead heading RMS (what least squares minimises).
double one_step_rms_deg(const YawModel& m, const std::vector<IdentSegment>& segments);

struct RefineOptions {
  std::size_t max_iterations = 30;
  double first_half_weight = 2.0;  // the start of a turn matters most to guidance (§3.4.3)
  double small_turn_weight = 2.0;  // turns up to 90 deg likewise
  double small_turn_deg = 90.0;
};
struct RefineReport {
  std::size_t iterations = 0;
  std::size_t best_iteration = 0;  // the one returned (early stopping on validation)
  double initial_cost = 0.0;
  double final_cost = 0.0;
};
// Simulation-error refinement: Levenberg-Marquardt on the weighted multi-step heading errors of
// whole predicted turns, starting from the least-squares model. Never returns a model whose cost
// is higher than the start. With validation windows it stops early: it returns the iterate with
// the lowest validation trajectory error (80 coefficients fitted to a few hundred noisy turns
// overfit otherwise).
YawModel refine_yaw_model(const YawModel& start, const std::vector<TurnWindow>& windows,
                          const RefineOptions& options = {}, RefineReport* report = nullptr,
                          const std::vector<TurnWindow>& validation = {});

}  // namespace avk::kinematics
