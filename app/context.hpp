#pragma once
// What the station's use cases share: the database (one connection per calling thread), the
// vehicle the station drives (when it has one) and the cache of each vehicle's CKT. Front ends
// hold one Context and call the use cases (app/*.hpp) with it.

#include <memory>
#include <optional>
#include <string>

#include "app/live_feed.hpp"
#include "app/vehicle_loop.hpp"

namespace avk::app {

class TableCache;
class TrafficWatch;
struct TrafficOptions;

class Context {
 public:
  // vehicle: the vehicle missions run on; none for a station that only reads (the command line,
  // an analyst's database). feed: where the vehicle's live state goes; must outlive the Context.
  explicit Context(std::string db_path, std::optional<VehicleLoopOptions> vehicle = std::nullopt,
                   LiveFeed* feed = nullptr);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Watches AIS traffic through gpsd from start() on (app/traffic_watch.hpp); before start().
  void watch_traffic(const TrafficOptions& options);
  // Marks missions whose process died as interrupted, starts the vehicle loop and the traffic
  // watch.
  void start();
  // Interrupts a running mission (stored, resumable), flushes and stops the vehicle.
  void shutdown(const std::string& reason = "the server stopped");

  // The database the use cases read and write (app/store_access.hpp).
  const std::string& db_path() const { return db_path_; }
  VehicleLoop* vehicle_loop() { return loop_.get(); }
  TableCache& tables() { return *tables_; }
  const TrafficWatch* traffic() const { return traffic_.get(); }

 private:
  std::string db_path_;
  SilentFeed silent_;
  std::unique_ptr<VehicleLoop> loop_;
  std::unique_ptr<TableCache> tables_;
  std::unique_ptr<TrafficWatch> traffic_;
};

}  // namespace avk::app
