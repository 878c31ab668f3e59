#include "store/sql/migrations.hpp"

#include <iterator>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "store/store.hpp"

namespace avk::store {

namespace {

// Each step moves the schema from version i to i + 1; the texts are the numbered files of
// store/migrations/<engine>/, embedded by store/CMakeLists.txt, which also checks that both
// engines have the same steps. Steps are append-only: a released step is never edited, because
// databases in the field have already run it.
constexpr std::string_view kSqliteSteps[] = {
#include "store/migration_steps_sqlite.inc"
};
constexpr std::string_view kPostgresqlSteps[] = {
#include "store/migration_steps_postgresql.inc"
};
static_assert(std::size(kSqliteSteps) == std::size(kPostgresqlSteps));

std::span<const std::string_view> steps(Engine engine) {
  if (engine == Engine::sqlite) return kSqliteSteps;
  return kPostgresqlSteps;
}

// Any constant: the key of the advisory lock that lets one station at a time migrate a shared
// PostgreSQL database.
constexpr std::int64_t kMigrationLock = 0x61766b5f736368;  // "avk_sch"

}  // namespace

int schema_version() {
  return static_cast<int>(std::size(kSqliteSteps));
}

std::string_view migration_step_sql(int index, Engine engine) {
  if (index < 0 || index >= schema_version())
    throw std::out_of_range("no migration step " + std::to_string(index));
  return steps(engine)[static_cast<std::size_t>(index)];
}

namespace sql {

int user_version(Database& db) {
  if (db.engine() == Engine::sqlite) {
    auto s = db.prepare("PRAGMA user_version");
    s.step();
    return static_cast<int>(s.column_int64(0));
  }
  // PostgreSQL has no user_version: a one-row table holds it, absent in a fresh database.
  auto has = db.prepare("SELECT to_regclass('avk_schema') IS NOT NULL");
  has.step();
  if (has.column_text(0) != "t") return 0;
  auto s = db.prepare("SELECT version FROM avk_schema");
  return s.step() ? static_cast<int>(s.column_int64(0)) : 0;
}

void migrate(Database& db) {
  // The version check and the steps share one write transaction, so two processes opening a
  // fresh database cannot both run step 1.
  Transaction tx(db);
  if (db.engine() == Engine::postgresql) {
    auto lock = db.prepare("SELECT pg_advisory_xact_lock(?)");
    lock.bind(1, kMigrationLock);
    lock.run();
    db.exec("CREATE TABLE IF NOT EXISTS avk_schema (version INTEGER NOT NULL)");
  }
  const int current = user_version(db);
  const int latest = schema_version();
  if (current > latest)
    throw StoreError("database schema version " + std::to_string(current) +
                     " is newer than this program supports (" + std::to_string(latest) +
                     "); upgrade AVK Station to open it");
  const auto texts = steps(db.engine());
  // Each text is a whole string literal, so data() ends with its terminating NUL.
  for (int v = current; v < latest; ++v)
    db.exec(texts[static_cast<std::size_t>(v)].data());
  if (current != latest) {
    if (db.engine() == Engine::sqlite) {
      // PRAGMA takes no bound parameters; the value is our own integer, not outside input.
      db.exec("PRAGMA user_version = " + std::to_string(latest));
    } else {
      db.exec("DELETE FROM avk_schema");
      auto set = db.prepare("INSERT INTO avk_schema (version) VALUES (?)");
      set.bind(1, latest);
      set.run();
    }
  }
  tx.commit();
}

}  // namespace sql

}  // namespace avk::store
