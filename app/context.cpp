#include "app/context.hpp"
#include "app/table_cache.hpp"

#include <map>

#include "app/ckt_tables.hpp"
#include "app/mission_liveness.hpp"
#include "app/store_access.hpp"
#include "app/traffic_watch.hpp"

namespace avk::app {

Context::Context(std::string db_path, std::optional<VehicleLoopOptions> vehicle, LiveFeed* feed)
    : db_path_(std::move(db_path)), tables_(std::make_unique<TableCache>()) {
  if (vehicle) loop_ = std::make_unique<VehicleLoop>(*vehicle, db_path_, feed ? *feed : silent_);
}

Context::~Context() {
  shutdown();
}

void Context::watch_traffic(const TrafficOptions& options) {
  traffic_ = std::make_unique<TrafficWatch>(options);
}

void Context::start() {
  mark_orphaned_missions_interrupted(store_of(*this));
  if (loop_) loop_->start();
  if (traffic_) traffic_->start();
}

void Context::shutdown(const std::string& reason) {
  if (traffic_) traffic_->stop();
  if (loop_) loop_->stop(reason);
}

store::Store& store_of(Context& ctx) {
  // Keyed by path: tests run several stations, each on its own database, on one thread.
  thread_local std::map<std::string, std::unique_ptr<store::Store>> connections;
  auto& c = connections[ctx.db_path()];
  if (!c) c = std::make_unique<store::Store>(ctx.db_path());
  return *c;
}

}  // namespace avk::app
