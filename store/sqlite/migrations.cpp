#include "store/sqlite/migrations.hpp"

#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

#include "store/store.hpp"

namespace avk::store {

namespace {

// Each step moves the schema from version i to i + 1; the texts are the numbered files of
// store/migrations/, embedded by store/CMakeLists.txt. Steps are append-only: a released step is
// never edited, because databases in the field have already run it.
constexpr std::string_view kMigrations[] = {
#include "store/migration_steps.inc"
};

}  // namespace

int schema_version() {
  return static_cast<int>(std::size(kMigrations));
}

std::string_view migration_step_sql(int index) {
  if (index < 0 || index >= schema_version())
    throw std::out_of_range("no migration step " + std::to_string(index));
  return kMigrations[static_cast<std::size_t>(index)];
}

namespace sqlite {

int user_version(Connection& db) {
  auto s = db.prepare("PRAGMA user_version");
  s.step();
  return static_cast<int>(s.column_int64(0));
}

void migrate(Connection& db) {
  // The version check and the steps share one write transaction, so two processes opening a
  // fresh file cannot both run step 1.
  Transaction tx(db);
  const int current = user_version(db);
  const int latest = schema_version();
  if (current > latest)
    throw StoreError("database schema version " + std::to_string(current) +
                     " is newer than this program supports (" + std::to_string(latest) +
                     "); upgrade AVK Station to open it");
  // Each text is a whole string literal, so data() ends with its terminating NUL.
  for (int v = current; v < latest; ++v)
    db.exec(kMigrations[static_cast<std::size_t>(v)].data());
  if (current != latest) {
    // PRAGMA takes no bound parameters; the value is our own integer, not outside input.
    const std::string set = "PRAGMA user_version = " + std::to_string(latest);
    db.exec(set.c_str());
  }
  tx.commit();
}

}  // namespace sqlite

}  // namespace avk::store
