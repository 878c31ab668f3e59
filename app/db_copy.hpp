#pragma once
// Moving a station's data between databases: an SQLite file and a PostgreSQL database, either
// way (docs/postgresql.md).

#include <cstdint>
#include <string>
#include <vector>

#include "app/result.hpp"

namespace avk::app {

struct TableCopied {
  std::string table;
  std::int64_t rows = 0;
};

// Copies everything `from` holds (missions, navigation, turns raw and normalised, events,
// models, snapshots, currents, harvests) into `to`, an empty database of either engine, ids kept
// and doubles exact; each table's rows counted in both before the copy commits. conflict when
// the target holds data; internal (naming the database) when either cannot be opened or the
// counts differ.
Result<std::vector<TableCopied>> copy_database(const std::string& from, const std::string& to);

}  // namespace avk::app
