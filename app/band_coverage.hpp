#pragma once
// Is the position band honest? The share of observed positions, at equal time, inside the
// band of a nominal share, on whole missions the table never saw: each ok turn of a test
// mission predicted from its command pose by the table of the other missions (over ground with
// the test mission's own estimated current, as the station would answer it live), and scored
// during the turn and on the steady run after it until the next command.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/corridor.hpp"

namespace avk::app {

class Context;

struct BandCoverageQuery {
  std::string vehicle_id;
  std::vector<std::int64_t> table_missions;  // empty: every mission of the vehicle but the tests
  std::vector<std::int64_t> test_missions;   // at least one
  double share = kinematics::kDefaultCorridorShare;
  double after_turn_s = 60.0;             // how long past the turn's end the run after it is scored
  std::optional<bool> speed_over_ground;  // none: the vehicle's
};

// The errors at equal time, along the predicted path's direction (+ ahead of the prediction) and
// across it (+ to its right), against the band's own sd in those directions.
struct ErrorStats {
  std::size_t n = 0;
  double along_mean_m = 0.0, along_rms_m = 0.0, along_band_sd_m = 0.0;  // band sd: RMS
  double cross_mean_m = 0.0, cross_rms_m = 0.0, cross_band_sd_m = 0.0;
};

struct SpeedCoverage {
  double speed_mps = 0.0;  // commanded
  std::size_t turns = 0;
  kinematics::Coverage during_turn, after_turn, all;
};

struct BandCoverage {
  std::vector<std::int64_t> table_missions, test_missions;
  double share = 0.0;
  std::size_t turns = 0;
  kinematics::Coverage during_turn, after_turn, all;
  ErrorStats errors_during_turn, errors_after_turn;
  std::vector<SpeedCoverage> by_speed;  // ascending
  bool speed_over_ground = true;
  double scatter_along_mps = 0.0, scatter_cross_mps = 0.0;
};

// not_found for an unknown mission or without turns to build from or to test; invalid_argument
// naming the field (test_missions, share, after_turn_s).
Result<BandCoverage> band_coverage(Context& ctx, const BandCoverageQuery& q);

}  // namespace avk::app
