#pragma once
// The station's store: vehicles, missions, recorded turns (raw and normalised), navigation
// samples, models, CKT snapshots, currents and harvests, each behind a repository interface that
// holds no engine type. Two engines stand behind them: an SQLite file (the embedded default) and a
// PostgreSQL database shared by several stations. The only code in the project that writes SQL is
// under store/.
//
// One Store is one connection, for one thread. Several Stores (threads or processes) may open the
// same database: SQLite's WAL mode and PostgreSQL's MVCC let readers see committed data while a
// writer works.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "store/ckt_snapshots.hpp"
#include "store/currents.hpp"
#include "store/database.hpp"
#include "store/harvests.hpp"
#include "store/mission_import.hpp"
#include "store/missions.hpp"
#include "store/models.hpp"
#include "store/navigation.hpp"
#include "store/turns.hpp"
#include "store/vehicles.hpp"

namespace avk::store {

// The schema version this code writes; opening a newer database is refused.
int schema_version();

// The SQL of migration step `index` (0-based: it moves a database from version index to
// index + 1) for the engine, so a test can build a database exactly as an older release left it.
// Throws std::out_of_range outside [0, schema_version()).
std::string_view migration_step_sql(int index, Engine engine = Engine::sqlite);

class Store {
 public:
  // Opens (creating if needed) and migrates the database: `db` is an SQLite file path (":memory:"
  // gives a private in-memory database) or a PostgreSQL target (is_postgresql_target: a
  // postgresql:// URI or a libpq keyword/value string such as "service=lab"). Throws StoreError
  // for a database newer than this code or any engine failure, StoreUnavailable when a
  // PostgreSQL server cannot be reached.
  explicit Store(const std::string& db);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  Engine engine() const;
  int user_version();
  std::string journal_mode();  // SQLite's journal mode; "server" for PostgreSQL
  bool integrity_check();      // PRAGMA integrity_check says "ok"; PostgreSQL answers a query

  // The station whose missions this Store creates (recorded with each mission); empty: none.
  void set_station_id(std::string station_id);
  // The connection itself, for store/ code that works across tables (copying a database).
  Database& database() { return *db_; }

  // The repositories share this Store's connection and live as long as it does.
  VehicleRepository& vehicles();
  MissionRepository& missions();
  TurnRepository& turns();
  NavigationRepository& navigation();
  ModelRepository& models();
  CktSnapshotRepository& ckt_snapshots();
  CurrentRepository& currents();
  HarvestRepository& harvests();

  // Stores the mission with everything it recorded in one transaction: on any failure the
  // database is left as it was. Returns the new mission id. Throws StoreError.
  std::int64_t import_mission(const MissionImport& m);

  // Test seams. The hook runs inside turns().add's transaction after each step ("turn_inserted"),
  // so a test can fail it halfway; overwrite_turn_json_for_testing corrupts a stored turn.
  void set_store_turn_hook_for_testing(std::function<void(std::string_view step)> hook);
  void overwrite_turn_json_for_testing(std::int64_t turn_id, std::string_view raw_json);

 private:
  struct Repositories;

  std::unique_ptr<Database> db_;
  std::unique_ptr<Repositories> repos_;
};

}  // namespace avk::store
