#pragma once
// The CKT as documents: a vehicle's table, one cell with its turns, the table over initial yaw
// rate.

#include <nlohmann/json.hpp>

#include "app/ckt_tables.hpp"
#include "app/yaw_rate_table.hpp"

namespace avk::server {

nlohmann::json ckt_summary_json(const app::VehicleTable& t);
// A cell on the side asked (app::ckt_cell): `side` "port" or "starboard", dheading_deg signed.
nlohmann::json ckt_cell_json(const app::SidedCell& s);
// The table over initial yaw rate: its coverage per slice, the model's scores where cells were
// measured, and the schema-4 CKT document (`ckt`).
nlohmann::json yaw_rate_table_json(const app::YawRateTable& t);

}  // namespace avk::server
