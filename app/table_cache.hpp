#pragma once
// The cache of each vehicle's table behind the station's predictions (app/ckt_tables.hpp): for
// app/ only, since it reads the store's revisions.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "app/ckt_tables.hpp"
#include "kinematics/ckt.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

// The tables predictions use, rebuilt when a vehicle's turns or imported table change (checked
// at most every `recheck`, so a prediction is a lookup).
class TableCache {
 public:
  explicit TableCache(std::chrono::milliseconds recheck = std::chrono::seconds(1))
      : recheck_(recheck) {}
  // include_harvested: the table of collection and harvested turns, cached apart from the
  // table of collection turns alone (the default), so the two never mix.
  Result<VehicleTable> get(Context& ctx, const std::string& vehicle_id,
                           bool include_harvested = false);
  // The table of the vehicle's ok turns without a mission or one turn (what a held-out
  // prediction answers from), built once per left-out set and dropped when the vehicle's turns
  // change, by the same check as get()'s. Null when no turn is left to build from. The table
  // keeps what a query reads, not the observed turns (Ckt::drop_observed_turns). At most
  // kHeldOutTables are kept (the least recently used goes first): a page asks for one left-out
  // set at a time.
  std::shared_ptr<const kinematics::Ckt> held_out(Context& ctx, const std::string& vehicle_id,
                                                  bool include_harvested,
                                                  const store::TurnsLeftOut& left_out);
  void forget(const std::string& vehicle_id);

  // From now on a table is re-read only after changed() (a shared database announces every
  // change: store::TableChangeListener) instead of at most every recheck.
  void follow_changes() { following_ = true; }
  // The vehicle's table may have changed; "" for any vehicle's (a change that names none, or
  // notifications that may have been missed).
  void changed(const std::string& vehicle_id);

  static constexpr std::size_t kHeldOutTables = 8;

 private:
  // What a vehicle's tables were built from: its newest ok turn, its latest imported table (read
  // only when it has no turns) and the revision of its missions' currents.
  struct Revision {
    std::int64_t turns = -1;
    std::int64_t snapshot = -1;
    std::int64_t current = -1;
    bool operator==(const Revision&) const = default;
  };
  struct Entry {
    std::mutex mutex;
    std::chrono::steady_clock::time_point checked{};
    std::pair<std::uint64_t, std::uint64_t> generation;  // of changed() when last read
    Revision seen;                                       // as last read from the store
    Revision value_from;                                 // what `value` was built from
    std::optional<VehicleTable> value;
  };
  struct HeldOutKey {
    std::string vehicle_id;
    bool include_harvested = false;
    std::optional<std::int64_t> mission_id;
    std::optional<std::int64_t> turn_id;
    auto operator<=>(const HeldOutKey&) const = default;
  };
  struct HeldOutTable {
    Revision built_from;
    std::shared_ptr<const kinematics::Ckt> table;
    std::uint64_t used = 0;  // a counter's value at the last use: the lowest goes first
  };
  Entry& entry(const std::string& vehicle_id, bool include_harvested);
  // Under e.mutex: the vehicle's revision, read from the store when `stale` or at most every
  // recheck_.
  const Revision& revision(Context& ctx, Entry& e, const std::string& vehicle_id,
                           bool include_harvested, bool stale);
  std::chrono::milliseconds recheck_;
  std::atomic<bool> following_{false};
  // Counts of changed(): for any vehicle, and per vehicle.
  std::pair<std::uint64_t, std::uint64_t> generation_of(const std::string& vehicle_id);
  std::mutex generation_mutex_;
  std::uint64_t any_generation_ = 1;
  std::map<std::string, std::uint64_t> vehicle_generation_;
  std::mutex mutex_;
  std::map<std::pair<std::string, bool>, std::unique_ptr<Entry>> entries_;
  // Apart from the entries: a held-out table takes a while to build, and predictions from the
  // full table must not wait for it.
  std::mutex held_out_mutex_;
  std::map<HeldOutKey, HeldOutTable> held_out_;
  std::uint64_t held_out_uses_ = 0;
};

}  // namespace avk::app
