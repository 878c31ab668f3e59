#pragma once
// The table over initial yaw rate in the CKT file (docs/ckt-format.md, schema 4): the document
// is an ordinary CKT file whose cells are the measured 2-D table (the 0 deg/s slice as measured),
// with an optional `yaw_rate_slices` array: per slice its initial_yaw_rate_dps and its cells in
// the format of `cells`, each with its `source` (measured or model). A file without slices
// (schema 1-4) loads as the 0 deg/s slice.

#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "kinematics/ckt3.hpp"

namespace avk::kinematics {

// At most this many slices in a file.
inline constexpr std::size_t kCktMaxYawRateSlices = 16;

nlohmann::json yaw_rate_ckt_to_json(const YawRateCkt& table);
std::string yaw_rate_ckt_to_json_string(const YawRateCkt& table);  // trailing newline

// Throws ParseError naming the JSON pointer of the bad field.
YawRateCkt yaw_rate_ckt_from_json(const nlohmann::json& doc);
YawRateCkt parse_yaw_rate_ckt_json(std::string_view text);

}  // namespace avk::kinematics
