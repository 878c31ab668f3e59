#pragma once
// What the station's use cases share: the database (one connection per calling thread), the
// vehicles the station drives (a fleet, each on its own loop, all in the one database) and the
// cache of each vehicle's CKT. Front ends hold one Context and call the use cases (app/*.hpp)
// with it.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "app/live_feed.hpp"
#include "app/vehicle_loop.hpp"

namespace avk::app {

class CollisionWatch;
struct CollisionWatchOptions;
class TableCache;
class TrafficWatch;
struct TrafficOptions;

// One vehicle of the station's fleet and where its live state goes (null: nowhere). The feed
// must outlive the Context.
struct FleetVehicle {
  VehicleLoopOptions options;
  LiveFeed* feed = nullptr;
};

class Context {
 public:
  // vehicle: the vehicle missions run on; none for a station that only reads (the command line,
  // an analyst's database). feed: where the vehicle's live state goes; must outlive the Context.
  explicit Context(std::string db_path, std::optional<VehicleLoopOptions> vehicle = std::nullopt,
                   LiveFeed* feed = nullptr);
  // A fleet: every vehicle with its own loop. Throws std::invalid_argument when two vehicles
  // would report the same id (their missions and turns could not be told apart).
  Context(std::string db_path, std::vector<FleetVehicle> fleet);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Watches AIS traffic through gpsd from start() on (app/traffic_watch.hpp); before start().
  void watch_traffic(const TrafficOptions& options);
  // Watches every pair of vehicles (and vehicle and AIS contact) for a predicted approach below
  // the standoff from start() on (app/collision_watch.hpp); before start().
  void watch_collisions(const CollisionWatchOptions& options);
  // Marks missions whose process died as interrupted, starts the vehicle loops and the traffic
  // watch.
  void start();
  // Interrupts the running missions (stored, resumable), flushes and stops the vehicles.
  void shutdown(const std::string& reason = "the server stopped");

  // The database the use cases read and write (app/store_access.hpp).
  const std::string& db_path() const { return db_path_; }
  // The live vehicle with this id; null when the station does not drive it.
  VehicleLoop* vehicle_loop(std::string_view vehicle_id);
  // Every live vehicle, in the order the station was given them.
  std::vector<VehicleLoop*> vehicle_loops();
  TableCache& tables() { return *tables_; }
  const TrafficWatch* traffic() const { return traffic_.get(); }
  // None when the station does not watch for collisions.
  CollisionWatch* collision_watch() { return collisions_.get(); }

 private:
  std::string db_path_;
  SilentFeed silent_;
  std::vector<std::unique_ptr<VehicleLoop>> loops_;
  std::unique_ptr<TableCache> tables_;
  // On a shared PostgreSQL database: follows other stations' changes (start() to shutdown()).
  std::jthread table_changes_;
  std::unique_ptr<TrafficWatch> traffic_;
  std::unique_ptr<CollisionWatch> collisions_;
};

}  // namespace avk::app
