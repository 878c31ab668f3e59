#pragma once
// Brings a database to schema_version() (store/store.hpp) by the numbered steps in
// store/migrations/.

#include "store/database.hpp"

namespace avk::store::sql {

// Throws StoreError for a database newer than this code.
void migrate(Database& db);
// PRAGMA user_version: the schema version the database is at.
int user_version(Database& db);

}  // namespace avk::store::sql
