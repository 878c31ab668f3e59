#pragma once
// The identification procedure around the yaw model: split the resampled data into training and
// validation by segment, fit, optionally refine on whole predicted turns, and measure both.

#include <cstddef>
#include <optional>
#include <vector>

#include "kinematics/resample.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::kinematics {

struct IdentificationOptions {
  YawModelForm form = YawModelForm::invariant;
  double history_s = 10.0;             // thesis: 10 s (40 samples at 4 Hz)
  std::optional<double> ridge_lambda;  // empty: chosen by validation error
  bool refine = false;
  RefineOptions refine_options{};
  // Long segments are cut into pieces of this length; every validation_every-th piece is held
  // out for validation (a split by segment, never by sample).
  double piece_length_s = 120.0;
  std::size_t validation_every = 4;
  double min_step_deg = 5.0;  // a desired-heading step that starts a validation turn
};

struct IdentificationResult {
  YawModel model;
  double train_one_step_rms_deg = 0.0;
  TrajectoryError train;
  TrajectoryError validation;
  std::size_t train_segments = 0;
  std::size_t validation_segments = 0;
  std::optional<RefineReport> refinement;
};

struct SegmentSplit {
  std::vector<IdentSegment> training;
  std::vector<IdentSegment> validation;
};
// The segments are taken by value (move them in when done with them): a long record is then held
// about once while it is cut and split, not three times.
SegmentSplit split_by_segment(std::vector<IdentSegment> segments, double piece_length_s,
                              std::size_t validation_every);

// Throws std::invalid_argument when the data cannot support the model (too short, no rate).
IdentificationResult identify_yaw_model(std::vector<IdentSegment> segments,
                                        const IdentificationOptions& options);

struct HistorySweepRow {
  double history_s = 0.0;
  std::size_t history = 0;
  double train_one_step_rms_deg = 0.0;
  TrajectoryError validation;
};
// Thesis Figure 3-9, over validation turns rather than one: the validation trajectory error for
// each history length.
std::vector<HistorySweepRow> sweep_history(std::vector<IdentSegment> segments,
                                           const IdentificationOptions& options,
                                           const std::vector<double>& history_s);

}  // namespace avk::kinematics
