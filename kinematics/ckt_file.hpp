#pragma once
// The CKT file (docs/ckt-format.md): a versioned JSON document, and a CSV of trajectory vertices
// for spreadsheets. Parsing is all-or-nothing: a table is returned only when every field checks.

#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "kinematics/ckt.hpp"

namespace avk::kinematics {

inline constexpr const char* kCktFormatName = "avk-ckt";
inline constexpr int kCktSchemaVersion = 1;

nlohmann::json ckt_to_json(const Ckt& table);
std::string ckt_to_json_string(const Ckt& table);  // pretty-printed, trailing newline

// Throws ParseError naming the JSON pointer of the bad field (or the line and column of a syntax
// error) for a corrupt, incomplete or wrong-version document.
Ckt ckt_from_json(const nlohmann::json& doc);
Ckt parse_ckt_json(std::string_view text);

// One row per trajectory vertex: speed_mps,dheading_deg,vertex_index,x_m,y_m.
std::string ckt_to_csv(const Ckt& table);

}  // namespace avk::kinematics
