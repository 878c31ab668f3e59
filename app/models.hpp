#pragma once
// The black-box yaw model (thesis §3.4): identification data from the stored navigation, fitting
// and storing a model, the history sweep, the stored models, and a model's view of one mission.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/model_view.hpp"
#include "app/result.hpp"
#include "kinematics/yaw_identification.hpp"

namespace avk::app {

class Context;

// Resampled navigation of the missions while the helm commanded motion (or imported logs);
// segments never span missions. not_found for an unknown mission, unsupported without data.
Result<std::vector<kinematics::IdentSegment>> identification_data(
    Context& ctx, const std::vector<std::int64_t>& missions,
    const kinematics::ResampleOptions& options);

// A model's view of one mission (the Model view's plot): the mission's identification data at the
// model's rate with the model's one-step-ahead and simulated headings beside the measured ones.
// Headings are unwrapped, as in IdentSegment; the desired heading is shown within 180 deg of the
// measured one at each sample. Samples without a prediction are empty.
struct HeadingSegment {
  double t0_s = 0.0;
  std::vector<double> heading_deg;
  std::vector<double> desired_heading_deg;
  // Predicted from the measured history ending one sample earlier: empty for the first warmup().
  std::vector<std::optional<double>> one_step_deg;
  // Free run: each prediction is fed back as history, driven by the measured desired heading.
  // It starts from the segment's first full history and restarts from the measured history at
  // every desired-heading step of at least restart_step_deg (one turn of the mission each), so
  // the plot shows how each turn is predicted rather than an hour-long drift. Empty for the first
  // warmup() samples.
  std::vector<std::optional<double>> simulated_deg;
};
struct ModelHeadings {
  std::int64_t model_id = 0;
  std::int64_t mission_id = 0;
  double dt_s = 0.0;
  std::size_t warmup = 0;
  double restart_step_deg = 0.0;
  std::vector<HeadingSegment> segments;
};
// At most max_samples samples in all, first segments first. not_found for an unknown model or
// mission, unsupported for a mission without guided navigation.
Result<ModelHeadings> model_headings(Context& ctx, std::int64_t model_id, std::int64_t mission,
                                     std::size_t max_samples, double restart_step_deg = 5.0);

struct FittedModel {
  ModelView stored;  // with its id
  kinematics::IdentificationResult result;
};
// Fits on the missions (each of the vehicle; invalid_argument "missions" otherwise) and stores the
// model with its provenance.
Result<FittedModel> fit_model(Context& ctx, const std::string& vehicle_id,
                              const std::vector<std::int64_t>& missions,
                              const kinematics::IdentificationOptions& options,
                              const kinematics::ResampleOptions& resample = {});

// Validation error against history length (thesis Figure 5-5), 2..20 s.
Result<std::vector<kinematics::HistorySweepRow>> sweep_model_history(
    Context& ctx, const std::string& vehicle_id, const std::vector<std::int64_t>& missions,
    const kinematics::IdentificationOptions& options,
    const kinematics::ResampleOptions& resample = {});

std::vector<ModelView> list_models(Context& ctx, const std::optional<std::string>& vehicle_id);
Result<ModelView> get_model(Context& ctx, std::int64_t model_id);
// The model given, or the vehicle's latest.
Result<ModelView> model_or_latest(Context& ctx, std::optional<std::int64_t> model_id,
                                  const std::string& vehicle_id);

}  // namespace avk::app
