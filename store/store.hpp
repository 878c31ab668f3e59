#pragma once
// The station's store: vehicles, missions, recorded turns (raw and normalised), navigation
// samples, models, CKT snapshots, currents and harvests, each behind a repository interface that
// holds no engine type, so another engine can stand behind the same interfaces. This Store is the
// SQLite engine: the only code in the project that writes SQL is under store/.
//
// One Store is one connection, for one thread. Several Stores (threads or processes) may open the
// same file: WAL mode lets readers see committed data while a writer works.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "store/ckt_snapshots.hpp"
#include "store/currents.hpp"
#include "store/harvests.hpp"
#include "store/mission_import.hpp"
#include "store/missions.hpp"
#include "store/models.hpp"
#include "store/navigation.hpp"
#include "store/sqlite.hpp"
#include "store/turns.hpp"
#include "store/vehicles.hpp"

namespace avk::store {

// The schema version this code writes; opening a newer database is refused.
int schema_version();

// The SQL of migration step `index` (0-based: it moves a database from version index to
// index + 1), so a test can build a database exactly as an older release left it. Throws
// std::out_of_range outside [0, schema_version()).
std::string_view migration_step_sql(int index);

class Store {
 public:
  // Opens (creating if needed) and migrates the database. ":memory:" gives a private in-memory
  // database. Throws StoreError for a database newer than this code or any SQLite failure.
  explicit Store(const std::string& path);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  int user_version();
  std::string journal_mode();
  bool integrity_check();  // PRAGMA integrity_check says "ok"

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

  Connection db_;
  std::unique_ptr<Repositories> repos_;
};

}  // namespace avk::store
