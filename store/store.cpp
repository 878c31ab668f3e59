#include "store/store.hpp"

#include <utility>

#include "store/postgresql.hpp"
#include "store/sql/migrations.hpp"
#include "store/sql/sql_ckt_snapshots.hpp"
#include "store/sql/sql_currents.hpp"
#include "store/sql/sql_harvests.hpp"
#include "store/sql/sql_import.hpp"
#include "store/sql/sql_missions.hpp"
#include "store/sql/sql_models.hpp"
#include "store/sql/sql_navigation.hpp"
#include "store/sql/sql_turns.hpp"
#include "store/sql/sql_vehicles.hpp"
#include "store/sqlite.hpp"

namespace avk::store {

// Every repository holds the Store's connection, which outlives them.
struct Store::Repositories {
  explicit Repositories(Database& db)
      : vehicles(db),
        missions(db),
        turns(db),
        navigation(db),
        models(db),
        ckt_snapshots(db),
        currents(db),
        harvests(db) {}

  sql::SqlVehicles vehicles;
  sql::SqlMissions missions;
  sql::SqlTurns turns;
  sql::SqlNavigation navigation;
  sql::SqlModels models;
  sql::SqlCktSnapshots ckt_snapshots;
  sql::SqlCurrents currents;
  sql::SqlHarvests harvests;
};

namespace {

std::unique_ptr<Database> open_database(const std::string& db) {
  if (is_postgresql_target(db)) return std::make_unique<PgConnection>(db);
  auto c = std::make_unique<Connection>(db);
  // Waiting up to 5 s for a lock rides out another writer's commit instead of failing at once.
  c->exec("PRAGMA busy_timeout = 5000");
  c->exec("PRAGMA foreign_keys = ON");
  // WAL: readers never block the writer nor see its uncommitted work. NORMAL synchronous is
  // durable against process crashes (only a power cut may lose the last commits) and avoids an
  // fsync per transaction, which nav ingest could not afford.
  c->exec("PRAGMA journal_mode = WAL");
  c->exec("PRAGMA synchronous = NORMAL");
  return c;
}

}  // namespace

Store::Store(const std::string& db) : db_(open_database(db)) {
  sql::migrate(*db_);
  repos_ = std::make_unique<Repositories>(*db_);
}

Store::~Store() = default;

Engine Store::engine() const {
  return db_->engine();
}

int Store::user_version() {
  return sql::user_version(*db_);
}

std::string Store::journal_mode() {
  if (db_->engine() != Engine::sqlite) return "server";
  auto s = db_->prepare("PRAGMA journal_mode");
  s.step();
  return s.column_text(0);
}

void Store::set_station_id(std::string station_id) {
  repos_->missions.set_station_id(std::move(station_id));
}

bool Store::integrity_check() {
  if (db_->engine() != Engine::sqlite) {
    auto s = db_->prepare("SELECT 1");
    return s.step() && s.column_int64(0) == 1;
  }
  auto s = db_->prepare("PRAGMA integrity_check");
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
  return sql::import_mission(*db_, m);
}

void Store::set_store_turn_hook_for_testing(std::function<void(std::string_view step)> hook) {
  repos_->turns.set_hook(std::move(hook));
}

void Store::overwrite_turn_json_for_testing(std::int64_t turn_id, std::string_view raw_json) {
  auto s = db_->prepare("UPDATE turns SET raw_json = ? WHERE id = ?");
  s.bind(1, raw_json).bind(2, turn_id);
  s.run();
}

}  // namespace avk::store
