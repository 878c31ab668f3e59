#include "app/context.hpp"
#include "app/table_cache.hpp"

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "app/ckt_tables.hpp"
#include "app/collision_watch.hpp"
#include "app/mission_liveness.hpp"
#include "app/station_identity.hpp"
#include "app/store_access.hpp"
#include "app/store_link.hpp"
#include "app/store_writer.hpp"
#include "app/traffic_watch.hpp"
#include "store/postgresql.hpp"

namespace avk::app {

Context::Context(std::string db_path, std::optional<VehicleLoopOptions> vehicle, LiveFeed* feed)
    : Context(std::move(db_path), vehicle ? std::vector<FleetVehicle>{{*vehicle, feed}}
                                          : std::vector<FleetVehicle>{}) {}

Context::Context(std::string db_path, std::vector<FleetVehicle> fleet)
    : db_path_(std::move(db_path)), tables_(std::make_unique<TableCache>()) {
  std::set<std::string> ids;
  for (auto& v : fleet) {
    const std::string id = planned_vehicle_info(v.options).id;
    if (!ids.insert(id).second)
      throw std::invalid_argument("two vehicles of the fleet are called '" + id + "'");
  }
  for (auto& v : fleet)
    loops_.push_back(
        std::make_unique<VehicleLoop>(std::move(v.options), db_path_, v.feed ? *v.feed : silent_));
}

VehicleLoop* Context::vehicle_loop(std::string_view vehicle_id) {
  for (auto& l : loops_)
    if (l->info().id == vehicle_id) return l.get();
  return nullptr;
}

std::vector<VehicleLoop*> Context::vehicle_loops() {
  std::vector<VehicleLoop*> out;
  for (auto& l : loops_)
    out.push_back(l.get());
  return out;
}

Context::~Context() {
  shutdown();
}

void Context::watch_traffic(const TrafficOptions& options) {
  traffic_ = std::make_unique<TrafficWatch>(options);
}

void Context::watch_collisions(const CollisionWatchOptions& options) {
  const double factor = loops_.empty() ? 1.0 : loops_.front()->options().realtime_factor;
  collisions_ = std::make_unique<CollisionWatch>(*this, options, factor);
}

namespace {

// Keeps the table cache told of every change other stations (and this one) make to a shared
// database; until the first LISTEN holds, and if it never does, the cache checks the store
// itself at most every second.
void follow_table_changes(const std::string& db, TableCache& tables, std::stop_token stop) {
  std::unique_ptr<store::TableChangeListener> listener;
  while (!stop.stop_requested()) {
    if (!listener) {
      try {
        listener = std::make_unique<store::TableChangeListener>(db);
      } catch (const store::StoreError&) {
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        continue;
      }
      tables.follow_changes();
      tables.changed("");
    }
    for (const std::string& vehicle : listener->wait(250))
      tables.changed(vehicle);
  }
}

}  // namespace

void Context::start() {
  mark_orphaned_missions_interrupted(store_of(*this));
  // Writes a run before this one spooled (the station stopped while the server was away) are
  // replayed first; if the server is still away the next write tries again.
  if (store::is_postgresql_target(db_path_) && std::filesystem::exists(spool_path()))
    StoreWriter(store_of(*this)).replay(true);
  if (store::is_postgresql_target(db_path_))
    table_changes_ = std::jthread(
        [this](std::stop_token stop) { follow_table_changes(db_path_, *tables_, stop); });
  for (auto& l : loops_)
    l->start();
  if (traffic_) traffic_->start();
  if (collisions_) collisions_->start();
}

void Context::shutdown(const std::string& reason) {
  if (table_changes_.joinable()) {
    table_changes_.request_stop();
    table_changes_.join();
  }
  if (collisions_) collisions_->stop();
  if (traffic_) traffic_->stop();
  // Every vehicle is told to stop first, so the fleet stops together rather than one by one.
  for (auto& l : loops_)
    l->request_stop(reason);
  for (auto& l : loops_)
    l->stop(reason);
}

store::Store& store_of(Context& ctx) {
  // Keyed by path: tests run several stations, each on its own database, on one thread.
  thread_local std::map<std::string, std::unique_ptr<store::Store>> connections;
  auto& c = connections[ctx.db_path()];
  if (!c) c = open_station_store(ctx.db_path());
  return *c;
}

}  // namespace avk::app
