#pragma once
// The water current and how a vehicle moves on a held heading as documents: estimates, what a
// mission's navigation shows, and the current and speed reference an answer assumed.

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/current.hpp"
#include "app/current_compensation.hpp"
#include "app/current_view.hpp"
#include "app/predict.hpp"
#include "app/vehicle_motion.hpp"
#include "kinematics/current_estimate.hpp"
#include "kinematics/drift_scatter.hpp"
#include "kinematics/speed_reference.hpp"
#include "kinematics/water_current.hpp"

namespace avk::server {

// {east_mps, north_mps, speed_mps, toward_deg, source}; null without a current.
nlohmann::json water_current_json(const std::optional<kinematics::WaterCurrent>& c,
                                  const std::optional<std::string>& source);
nlohmann::json current_estimate_json(const kinematics::CurrentEstimate& e);
// The stream's `current` topic and GET .../current: an estimate with its mission and revision.
nlohmann::json current_json(const std::string& vehicle_id, const app::CurrentView& c);
// An estimate from a mission's navigation, with the stored one (null when none).
nlohmann::json mission_current_json(const app::MissionCurrent& c,
                                    const std::optional<app::CurrentView>& stored);
// An estimate stored (`avk current estimate --store`): mission_current_json of it with the
// number of turns given their water-frame form (water_frame_turns).
nlohmann::json applied_current_json(const app::AppliedCurrent& a);
// `avk current compare`: the table's and the test missions, each test mission's current, and
// every test turn's path error with and without it.
nlohmann::json compensation_comparison_json(const std::string& vehicle_id,
                                            const app::CompensationComparison& c);
// {legs, rms_over_ground_mps, rms_through_water_mps, separation_mps, identified}; identified is
// "over_ground", "through_water" or null (undetermined); null when not evaluated.
nlohmann::json speed_reference_evidence_json(
    const std::optional<kinematics::SpeedReferenceEvidence>& e);
// {along_mps, cross_mps, legs, mean_leg_s}; null when not measured.
nlohmann::json drift_scatter_json(const std::optional<kinematics::DriftScatter>& d);
// GET /vehicles/{vid}/motion and `avk vehicle motion --format json`.
nlohmann::json vehicle_motion_json(const app::VehicleMotion& m);

// The current an answer applied, with its source, and the 1-sigma uncertainty of the estimate
// it came from: of each component, and of its speed and direction when there is a current.
nlohmann::json answer_current_json(const std::optional<kinematics::WaterCurrent>& current,
                                   const std::optional<std::string>& source,
                                   const std::optional<std::array<double, 3>>& covariance);
// The speed an answer's vehicle holds: {value: over_ground or through_water, source}.
nlohmann::json speed_reference_json(const app::AnswerMotion& motion);

}  // namespace avk::server
