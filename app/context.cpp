#include "app/context.hpp"

#include <map>

#include "app/ckt_tables.hpp"
#include "app/mission_liveness.hpp"

namespace avk::app {

Context::Context(std::string db_path, std::optional<VehicleLoopOptions> vehicle, LiveFeed* feed)
    : db_path_(std::move(db_path)), tables_(std::make_unique<TableCache>()) {
  if (vehicle) loop_ = std::make_unique<VehicleLoop>(*vehicle, db_path_, feed ? *feed : silent_);
}

Context::~Context() {
  shutdown();
}

void Context::start() {
  mark_orphaned_missions_interrupted(db());
  if (loop_) loop_->start();
}

void Context::shutdown(const std::string& reason) {
  if (loop_) loop_->stop(reason);
}

store::Store& Context::db() {
  // Keyed by path: tests run several stations, each on its own database, on one thread.
  thread_local std::map<std::string, std::unique_ptr<store::Store>> connections;
  auto& c = connections[db_path_];
  if (!c) c = std::make_unique<store::Store>(db_path_);
  return *c;
}

}  // namespace avk::app
