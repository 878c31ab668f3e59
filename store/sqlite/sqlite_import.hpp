#pragma once
// A whole mission from another station, written across the aggregates in one transaction.

#include <cstdint>

#include "store/mission_import.hpp"
#include "store/sqlite.hpp"

namespace avk::store::sqlite {

// Store::import_mission on SQLite.
std::int64_t import_mission(Connection& db, const MissionImport& m);

}  // namespace avk::store::sqlite
