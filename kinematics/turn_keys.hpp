#pragma once
// The keys of a turn record, written once for both of its encodings: the JSON document
// (turn_json) and the one-line text record (turn_text). Both read and write every key listed
// here, so a field added to the metadata cannot reach one encoding and miss the other.

#include <array>
#include <cstddef>
#include <optional>

#include "kinematics/turn_sequence.hpp"

namespace avk::kinematics {

inline constexpr const char* kTurnVehicleIdKey = "vehicle_id";
inline constexpr const char* kTurnMissionIdKey = "mission_id";
inline constexpr const char* kTurnStatusKey = "status";
inline constexpr const char* kTurnStatusReasonKey = "status_reason";
inline constexpr const char* kTurnNormalizedKey = "normalized";
inline constexpr const char* kTurnWarningsKey = "warnings";
inline constexpr const char* kTurnSamplesKey = "samples";

struct TurnMetaDoubleKey {
  const char* name;
  double TurnMeta::*member;
};

// The metadata's required numbers, in the order both encodings write them.
inline constexpr std::array<TurnMetaDoubleKey, 7> kTurnMetaDoubles = {{
    {"commanded_speed_mps", &TurnMeta::commanded_speed_mps},
    {"goal_dheading_deg", &TurnMeta::goal_dheading_deg},
    {"observed_dheading_deg", &TurnMeta::observed_dheading_deg},
    {"initial_heading_deg", &TurnMeta::initial_heading_deg},
    {"initial_speed_mps", &TurnMeta::initial_speed_mps},
    {"start_time_s", &TurnMeta::start_time_s},
    {"end_time_s", &TurnMeta::end_time_s},
}};

struct TurnOptionalDoubleKey {
  const char* name;
  std::optional<double> TurnMeta::*member;
};

// The metadata's optional numbers: written only when the turn has the value, so records of
// turns without them read as they always did.
inline constexpr std::array<TurnOptionalDoubleKey, 2> kTurnOptionalMetaDoubles = {{
    {"initial_yaw_rate_dps", &TurnMeta::initial_yaw_rate_dps},
    {"speed_after_mps", &TurnMeta::speed_after_mps},
}};

// The columns of a sample, in the order both encodings write them.
inline constexpr std::size_t kTurnSampleArity = 5;
inline constexpr std::array<const char*, kTurnSampleArity> kTurnSampleFields = {
    "t_s", "x_m", "y_m", "heading_deg", "speed_mps"};
inline constexpr std::array<double TurnSample::*, kTurnSampleArity> kTurnSampleMembers = {
    &TurnSample::t_s, &TurnSample::x_m, &TurnSample::y_m, &TurnSample::heading_deg,
    &TurnSample::speed_mps};

}  // namespace avk::kinematics
