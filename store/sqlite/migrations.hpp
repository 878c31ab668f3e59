#pragma once
// Brings a database to schema_version() (store/store.hpp) by the numbered steps in
// store/migrations/.

#include "store/sqlite.hpp"

namespace avk::store::sqlite {

// Throws StoreError for a database newer than this code.
void migrate(Connection& db);
// PRAGMA user_version: the schema version the database is at.
int user_version(Connection& db);

}  // namespace avk::store::sqlite
