#pragma once
// Copying a whole database between engines (SQLite file <-> PostgreSQL, or the same engine):
// every table, ids kept, doubles exact, in one transaction on the target.

#include <cstdint>
#include <string>
#include <vector>

#include "store/store.hpp"

namespace avk::store {

struct TableCount {
  std::string table;
  std::int64_t rows = 0;
};

// Copies everything `from` holds into `to`, which must be empty (no vehicle, mission or other
// row): a copy never merges. The rows of each table are counted in the source and in the target
// before the target commits; any difference throws and leaves the target as it was. Returns
// the count of every table, in copy order. Throws StoreError.
std::vector<TableCount> copy_database(Store& from, Store& to);

}  // namespace avk::store
