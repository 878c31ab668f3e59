#include "kinematics/yaw_identification.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avk::kinematics {

SegmentSplit split_by_segment(std::vector<IdentSegment> segments, double piece_length_s,
                              std::size_t validation_every) {
  SegmentSplit split;
  auto pieces = split_long_segments(std::move(segments), piece_length_s);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const bool held_out = validation_every > 1 && i % validation_every == validation_every - 1;
    (held_out ? split.validation : split.training).push_back(std::move(pieces[i]));
  }
  return split;
}

namespace {

std::size_t samples_of(double history_s, double dt_s) {
  const auto n = static_cast<std::size_t>(std::lround(history_s / dt_s));
  if (n == 0) throw std::invalid_argument("history must be at least one sample");
  return n;
}

}  // namespace

IdentificationResult identify_yaw_model(std::vector<IdentSegment> segments,
                                        const IdentificationOptions& options) {
  if (segments.empty()) throw std::invalid_argument("no identification data");
  const double dt_s = segments.front().dt_s;
  const SegmentSplit split =
      split_by_segment(std::move(segments), options.piece_length_s, options.validation_every);
  if (split.training.empty()) throw std::invalid_argument("no training data after the split");
  IdentificationResult r;
  r.train_segments = split.training.size();
  r.validation_segments = split.validation.size();
  FitOptions fo;
  fo.form = options.form;
  fo.history = samples_of(options.history_s, dt_s);
  fo.ridge_lambda = options.ridge_lambda;
  r.model = fit_yaw_model(split.training, fo, split.validation);
  r.model.speed = fit_speed_model(split.training);
  const auto train_windows = turn_windows(split.training, r.model.warmup(), options.min_step_deg);
  if (options.refine) {
    RefineReport report;
    r.model =
        refine_yaw_model(r.model, train_windows, options.refine_options, &report,
                         turn_windows(split.validation, r.model.warmup(), options.min_step_deg));
    r.refinement = report;
  }
  r.train_one_step_rms_deg = one_step_rms_deg(r.model, split.training);
  r.train = trajectory_error(r.model, train_windows);
  r.validation = trajectory_error(
      r.model, turn_windows(split.validation, r.model.warmup(), options.min_step_deg));
  return r;
}

std::vector<HistorySweepRow> sweep_history(std::vector<IdentSegment> segments,
                                           const IdentificationOptions& options,
                                           const std::vector<double>& history_s) {
  if (segments.empty() || history_s.empty()) return {};
  const double dt_s = segments.front().dt_s;
  const SegmentSplit split =
      split_by_segment(std::move(segments), options.piece_length_s, options.validation_every);
  // Every history length is scored on the same turns: those the longest history can predict.
  std::size_t longest = 0;
  for (double h : history_s)
    longest = std::max(longest, samples_of(h, dt_s));
  const auto windows = turn_windows(split.validation, longest + 1, options.min_step_deg);
  const auto train_windows = turn_windows(split.training, longest + 1, options.min_step_deg);
  std::vector<HistorySweepRow> rows;
  for (double h : history_s) {
    FitOptions fo;
    fo.form = options.form;
    fo.history = samples_of(h, dt_s);
    fo.ridge_lambda = options.ridge_lambda;
    YawModel m = fit_yaw_model(split.training, fo, split.validation);
    if (options.refine)
      m = refine_yaw_model(m, train_windows, options.refine_options, nullptr, windows);
    rows.push_back(
        {h, m.history, one_step_rms_deg(m, split.training), trajectory_error(m, windows)});
  }
  return rows;
}

}  // namespace avk::kinematics
