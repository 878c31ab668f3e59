#pragma once
// The CKT file (docs/ckt-format.md): a versioned JSON document, and a CSV of trajectory vertices
// for spreadsheets. Parsing is all-or-nothing: a table is returned only when every field checks.

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "kinematics/ckt.hpp"

namespace avk::kinematics {

inline constexpr const char* kCktFormatName = "avk-ckt";
// Version 2 adds the mean kind (options/mean_kind) and each cell's corridor and short_of_goal
// flag, all optional; version 1 files still load (their mean kind is x_grid, they have no
// corridors).
// Version 4 adds the optional yaw_rate_slices (the table over initial yaw rate, ckt3_file.hpp).
inline constexpr int kCktSchemaVersion = 4;
inline constexpr int kCktOldestSchemaVersion = 1;

// Bounds of an imported table (docs/ckt-format.md). A CKT file comes from outside: an unbounded
// top speed of 200 m/s made the first prediction build a 123 MB fine table, and 1e300 overflowed
// its row count. The bounds are far past any surface vehicle the station drives.
inline constexpr double kCktMaxSpeedMps = 20.0;
inline constexpr std::size_t kCktMaxGridSpeeds = 64;
inline constexpr std::size_t kCktMaxGridDheadings = 180;
// Trajectory vertices, spline knots and control points, polynomial coefficients: each list.
inline constexpr std::size_t kCktMaxListLength = 10000;

nlohmann::json ckt_to_json(const Ckt& table);
std::string ckt_to_json_string(const Ckt& table);  // pretty-printed, trailing newline

// Throws ParseError naming the JSON pointer of the bad field (or the line and column of a syntax
// error) for a corrupt, incomplete or wrong-version document.
Ckt ckt_from_json(const nlohmann::json& doc);
Ckt parse_ckt_json(std::string_view text);
// The JSON of a CKT file's text, with its syntax errors reported as parse_ckt_json reports them.
nlohmann::json parse_ckt_document(std::string_view text);

// One row per trajectory vertex: speed_mps,dheading_deg,vertex_index,x_m,y_m.
std::string ckt_to_csv(const Ckt& table);

}  // namespace avk::kinematics
