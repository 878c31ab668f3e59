#pragma once
// What a Foxglove scene of a turn shows besides the track: each method's prediction placed at the
// turn's start pose (the same answers as GET /vehicles/{vid}/predict) and the CKT cell that
// answered. Shared by the live connection and a mission's MCAP file.

#include <optional>
#include <string>
#include <vector>

#include "app/foxglove/messages.hpp"
#include "kinematics/geometry.hpp"

namespace avk::app {
class Context;
}

namespace avk::app::foxglove {

struct ScenePredictions {
  std::vector<ScenePrediction> predictions;  // a method that cannot answer is left out
  std::optional<std::string> cell_label;     // the table's cell; none without a table
};

// dheading_deg signed (+ right).
ScenePredictions scene_predictions(Context& ctx, const std::string& vehicle_id, double speed_mps,
                                   double dheading_deg, const kinematics::Pose& start);

}  // namespace avk::app::foxglove
