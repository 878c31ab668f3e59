#include "store/store.hpp"

#include <utility>

#include "store/sqlite/migrations.hpp"
#include "store/sqlite/sqlite_ckt_snapshots.hpp"
#include "store/sqlite/sqlite_currents.hpp"
#include "store/sqlite/sqlite_harvests.hpp"
#include "store/sqlite/sqlite_import.hpp"
#include "store/sqlite/sqlite_missions.hpp"
#include "store/sqlite/sqlite_models.hpp"
#include "store/sqlite/sqlite_navigation.hpp"
#include "store/sqlite/sqlite_turns.hpp"
#include "store/sqlite/sqlite_vehicles.hpp"

namespace avk::store {

// Every repository holds the Store's connection, which outlives them.
struct Store::Repositories {
  explicit Repositories(Connection& db)
      : vehicles(db),
        missions(db),
        turns(db),
        navigation(db),
        models(db),
        ckt_snapshots(db),
        currents(db),
        harvests(db) {}

  sqlite::SqliteVehicles vehicles;
  sqlite::SqliteMissions missions;
  sqlite::SqliteTurns turns;
  sqlite::SqliteNavigation navigation;
  sqlite::SqliteModels models;
  sqlite::SqliteCktSnapshots ckt_snapshots;
  sqlite::SqliteCurrents currents;
  sqlite::SqliteHarvests harvests;
};

Store::Store(const std::string& path) : db_(path) {
  // Waiting up to 5 s for a lock rides out another writer's commit instead of failing at once.
  db_.exec("PRAGMA busy_timeout = 5000");
  db_.exec("PRAGMA foreign_keys = ON");
  // WAL: readers never block the writer nor see its uncommitted work. NORMAL synchronous is
  // durable against process crashes (only a power cut may lose the last commits) and avoids an
  // fsync per transaction, which nav ingest could not afford.
  db_.exec("PRAGMA journal_mode = WAL");
  db_.exec("PRAGMA synchronous = NORMAL");
  sqlite::migrate(db_);
  repos_ = std::make_unique<Repositories>(db_);
}

Store::~Store() = default;

int Store::user_version() {
  return sqlite::user_version(db_);
}

std::string Store::journal_mode() {
  auto s = db_.prepare("PRAGMA journal_mode");
  s.step();
  return s.column_text(0);
}

bool Store::integrity_check() {
  auto s = db_.prepare("PRAGMA integrity_check");
  // A healthy database answers a single row "ok"; anything else lists problems.
  if (!s.step()) return false;
  const bool ok = s.column_text(0) == "ok";
  return ok && !s.step();
}

VehicleRepository& Store::vehicles() {
  return repos_->vehicles;
}
MissionRepository& Store::missions() {
  return repos_->missions;
}
TurnRepository& Store::turns() {
  return repos_->turns;
}
NavigationRepository& Store::navigation() {
  return repos_->navigation;
}
ModelRepository& Store::models() {
  return repos_->models;
}
CktSnapshotRepository& Store::ckt_snapshots() {
  return repos_->ckt_snapshots;
}
CurrentRepository& Store::currents() {
  return repos_->currents;
}
HarvestRepository& Store::harvests() {
  return repos_->harvests;
}

std::int64_t Store::import_mission(const MissionImport& m) {
  return sqlite::import_mission(db_, m);
}

void Store::set_store_turn_hook_for_testing(std::function<void(std::string_view step)> hook) {
  repos_->turns.set_hook(std::move(hook));
}

void Store::overwrite_turn_json_for_testing(std::int64_t turn_id, std::string_view raw_json) {
  auto s = db_.prepare("UPDATE turns SET raw_json = ? WHERE id = ?");
  s.bind(1, raw_json).bind(2, turn_id);
  s.run();
}

}  // namespace avk::store
