#pragma once
// Rows for the store's mission tests: a mission of a registered vehicle, a synthetic arc turn with
// noise on position and heading, and the check of a mean and standard deviation.

#include <gtest/gtest.h>

#include "support/schema_downgrade.hpp"
#include "support/temp_db.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/turn_json.hpp"
#include "store/store.hpp"
#include "support/synthetic_turns.hpp"

namespace avk::testing::mission_rows {

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using avk::testing::TempDb;
using namespace avk::store;

inline std::int64_t make_mission(Store& s, const std::string& vehicle = "usim-1") {
  s.vehicles().upsert({vehicle, "usim", 2.0, 1.2});
  return s.missions().create(vehicle, "collection", "{}");
}

inline TurnSequence arc(double speed_mps, double dheading_deg, unsigned seed = 1,
                        const std::string& vehicle = "usim-1") {
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = speed_mps;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.position_noise_m = 0.05;
  spec.heading_noise_deg = 0.5;
  spec.start = {12.5, -3.25, 33.0 + seed};
  spec.vehicle_id = vehicle;
  return avk::testing::make_arc_turn(spec);
}

inline void expect_mean_sd(const std::optional<avk::kinematics::MeanSd>& got, double mean,
                           double sd) {
  ASSERT_TRUE(got.has_value());
  EXPECT_NEAR(got->mean, mean, 1e-9);
  EXPECT_NEAR(got->sd, sd, 1e-9);
}

}  // namespace avk::testing::mission_rows
