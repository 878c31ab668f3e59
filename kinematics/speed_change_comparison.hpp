#pragma once
// The comparison of predictions for turns with a speed change, scored like the
// constant-speed ones (predictive_comparison.hpp): every predictor on turns it was not built
// from, by mean distance at equal arc length (path_metric.hpp).
//
// For each speed-change turn, grouped in cells of (u0, u1, |dheading|):
// - measured: the SpeedChangeTable built from the OTHER speed-change turns, at the turn's pair
//   (leave-one-out; interpolated across heading changes when its own cell has no other turn);
//   absent when no other turn of the pair exists;
// - retimed_measured: the constant-speed CKT turn at u0 re-timed by the speed response measured
//   from the other speed-change turns;
// - retimed_model: the same re-timed by the yaw model's speed model (with a model);
// - model: the yaw model flown with its speed model and the command stepping to u1;
// - constant_speed: the constant-speed CKT turn at u0 as it is, the speed change ignored (what
//   the table answered before it knew speed changes), for scale;
// - instantaneous: the ray along the goal heading.
// The constant-speed CKT holds none of these turns (Ckt::build leaves them out). The observed
// turn is stationed by its recorded speed (s = integral of speed dt), not by u0 x t as a
// constant-speed turn is: its speed changes by design.

#include <functional>
#include <optional>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/path_metric.hpp"
#include "kinematics/predictive_comparison.hpp"
#include "kinematics/speed_response.hpp"

namespace avk::kinematics {

// A normalised turn of |dheading| from u0 with the command stepping to u1 (the model).
using SpeedChangePredictor = std::function<Polyline(double u0, double u1, double dheading_deg)>;

struct SpeedChangeCellScores {
  double from_mps = 0.0;
  double to_mps = 0.0;
  double dheading_deg = 0.0;
  std::size_t n_turns = 0;
  double span_m = 0.0;  // the longest turn of the cell
  HeldOutScores instantaneous;
  std::optional<HeldOutScores> measured, retimed_measured, retimed_model, model, constant_speed;
};

// A turn's path stationed by its recorded speed. Throws as stationed_by_time.
StationedPath stationed_by_speed(const TurnSequence& turn);

// turns: any turns (only ok ones with a speed change are scored); table: the constant-speed CKT
// (the re-timed predictions' base, skipped where it cannot answer u0); model_response and model:
// optional.
std::vector<SpeedChangeCellScores> compare_speed_changes(
    const std::vector<TurnSequence>& turns, const Ckt& table,
    const std::optional<SpeedResponse>& model_response, const SpeedChangePredictor* model,
    const CktOptions& options = {});

// Median over cells of a method's cell means (path distance); empty when no cell has it.
enum class SpeedChangeMethod {
  measured,
  retimed_measured,
  retimed_model,
  model,
  constant_speed,
  instantaneous
};
inline constexpr SpeedChangeMethod kSpeedChangeMethods[] = {
    SpeedChangeMethod::measured,       SpeedChangeMethod::retimed_measured,
    SpeedChangeMethod::retimed_model,  SpeedChangeMethod::model,
    SpeedChangeMethod::constant_speed, SpeedChangeMethod::instantaneous};
const char* to_string(SpeedChangeMethod m);
std::optional<double> median_speed_change_path_m(const std::vector<SpeedChangeCellScores>& cells,
                                                 SpeedChangeMethod method);
const HeldOutScores* scores_of(const SpeedChangeCellScores& cell, SpeedChangeMethod method);

}  // namespace avk::kinematics
