#pragma once
// A whole mission from another station, written across the aggregates in one transaction.

#include <cstdint>

#include "store/database.hpp"
#include "store/mission_import.hpp"

namespace avk::store::sql {

// Store::import_mission on either engine.
std::int64_t import_mission(Database& db, const MissionImport& m);

}  // namespace avk::store::sql
