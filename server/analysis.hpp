#pragma once
// The analyses the command line and the server both offer over the store: identification data,
// fitting and storing a yaw model, the prediction comparison and single predictions, as
// structures and as the JSON/CSV documents both serve.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/prediction_comparison.hpp"
#include "kinematics/yaw_identification.hpp"
#include "store/store.hpp"

namespace avk::server {

// Resampled navigation of the missions while the helm commanded motion (or imported logs);
// segments never span missions. Throws std::runtime_error for an unknown mission or no data.
std::vector<kinematics::IdentSegment> identification_data(
    store::Store& db, const std::vector<std::int64_t>& missions,
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
  double dt_s = 0.0;
  std::size_t warmup = 0;
  double restart_step_deg = 0.0;
  std::vector<HeadingSegment> segments;
};
// At most max_samples samples in all, first segments first. Throws std::runtime_error for an
// unknown mission or one without guided navigation.
ModelHeadings model_headings(store::Store& db, const kinematics::YawModel& model,
                             std::int64_t mission, std::size_t max_samples,
                             double restart_step_deg = 5.0);
nlohmann::json model_headings_json(const ModelHeadings& h);

struct FittedModel {
  store::StoredModel stored;  // with its id
  kinematics::IdentificationResult result;
};
FittedModel fit_and_store_model(store::Store& db, const std::string& vehicle_id,
                                const std::vector<std::int64_t>& missions,
                                const kinematics::IdentificationOptions& options,
                                const kinematics::ResampleOptions& resample = {});
nlohmann::json model_json(const store::StoredModel& m);

// The two non-table predictions `avk predict` and GET /predict answer, in the CKT's frame: from
// the origin heading north, a left turn (dheading < 0) the mirror image of the right one.
kinematics::Polyline model_turn(const kinematics::YawModel& m, double speed_mps,
                                double dheading_deg, double completion_threshold_deg = 5.0,
                                bool use_speed_model = false);
// The current practice: the vehicle is on the new heading at once; drawn for 20 s of travel.
kinematics::Polyline instantaneous_turn_ray(double speed_mps, double dheading_deg);

struct Comparison {
  std::string vehicle_id;
  std::optional<store::StoredModel> model;
  kinematics::Ckt table;
  std::vector<kinematics::CellComparison> cells;
};
// The comparison over the vehicle's ok turns (of the missions; empty: all). Throws
// std::runtime_error when there are none.
Comparison compare_from_store(store::Store& db, const std::string& vehicle_id,
                              const std::vector<std::int64_t>& missions,
                              std::optional<store::StoredModel> model,
                              double completion_threshold_deg = 5.0);
nlohmann::json comparison_json(const Comparison& c);
std::string comparison_csv(const Comparison& c);

}  // namespace avk::server
