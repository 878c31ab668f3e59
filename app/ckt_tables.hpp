#pragma once
// A vehicle's Cached Kinematics Table as the station answers with it: built from the vehicle's
// own ok turns (in the water frame where their mission's current is known, app/current.hpp), or,
// when it has none, its latest imported table. One rule for every front end.

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/speed_change_table.hpp"
#include "kinematics/speed_response.hpp"
#include "store/store.hpp"

namespace avk::app {

class Context;

enum class TableSource { turns, imported };
const char* to_string(TableSource s);

struct VehicleTable {
  std::string vehicle_id;
  bool include_harvested = false;  // built from collection and harvested turns
  TableSource source = TableSource::turns;
  std::optional<std::int64_t> snapshot_id;  // the imported table answering
  std::shared_ptr<const kinematics::Ckt> table;
  // The fine table predictions look up; none when the table holds no turn.
  std::shared_ptr<const kinematics::MaterializedCkt> fine;
  // The measured cells of the vehicle's speed-change turns, and the speed response averaged
  // from them; empty for an imported table.
  std::shared_ptr<const kinematics::SpeedChangeTable> speed_changes;
  std::optional<kinematics::SpeedResponse> measured_speed_response;
};

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
    Revision seen;        // as last read from the store
    Revision value_from;  // what `value` was built from
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
  std::mutex mutex_;
  std::map<std::pair<std::string, bool>, std::unique_ptr<Entry>> entries_;
  // Apart from the entries: a held-out table takes a while to build, and predictions from the
  // full table must not wait for it.
  std::mutex held_out_mutex_;
  std::map<HeldOutKey, HeldOutTable> held_out_;
  std::uint64_t held_out_uses_ = 0;
};

// The vehicle's table (not_found when it has no turns and no imported table). Built from its
// collection turns, and its harvested turns too when include_harvested.
Result<VehicleTable> vehicle_table(Context& ctx, const std::string& vehicle_id,
                                   bool include_harvested = false);

// A cell on the side asked. The table stores right turns, so a port (negative) heading change is
// the cell of its magnitude mirrored about the start heading (x -> -x), as a left prediction is;
// the polylines here are on the side asked, the statistics are the cell's.
struct SidedCell {
  kinematics::CktCell cell;
  kinematics::TurnSide side = kinematics::TurnSide::right;
  double dheading_deg = 0.0;                // signed, as asked
  std::vector<kinematics::Polyline> turns;  // each observed turn's normalised points
  kinematics::Polyline mean_turn;
  kinematics::Polyline trajectory;
  std::optional<kinematics::Polyline> fit;  // the fit sampled every kFitSampleStepM
};
inline constexpr double kFitSampleStepM = 0.1;

// One cell of the vehicle's table at a grid speed and signed heading change (+ starboard, - port;
// not_found off the grid).
Result<SidedCell> ckt_cell(Context& ctx, const std::string& vehicle_id, double speed_mps,
                           double dheading_deg, bool include_harvested = false);

// The table to hand out as a CKT file: the vehicle's table, named after it.
Result<kinematics::Ckt> ckt_for_export(Context& ctx, const std::string& vehicle_id,
                                       bool include_harvested = false);

// Parses a CKT file and stores it as the vehicle's imported table. invalid_argument naming
// "body" when the file is not a CKT file or is another vehicle's, "vehicle_id" for an id
// vehicle::vehicle_id_problem refuses, "created_utc" for one longer than kMaxCreatedUtcBytes;
// nothing is stored then.
inline constexpr std::size_t kMaxCreatedUtcBytes = 64;
struct ImportedTable {
  std::int64_t snapshot_id = 0;
  std::string vehicle_id;
};
Result<ImportedTable> import_ckt(Context& ctx, const std::string& vehicle_id,
                                 const std::string& ckt_file_text);

// Builds a table from the stored ok turns of the missions (empty: all) of one vehicle (in the water
// frame where their mission's current is known) and keeps
// it as a snapshot with the missions it came from: the record of which table guidance was given.
// Harvested turns are left out unless include_harvested; harvested_turns counts those used.
struct BuiltTable {
  kinematics::Ckt table;
  kinematics::CktBuildReport report;
  std::int64_t snapshot_id = 0;
  std::size_t harvested_turns = 0;  // harvested turns among the ok turns the table was built from
};
Result<BuiltTable> build_ckt(Context& ctx, const std::string& vehicle_id,
                             const std::vector<std::int64_t>& missions,
                             const kinematics::CktOptions& options,
                             std::optional<double> vehicle_length_m = std::nullopt,
                             bool include_harvested = false);

}  // namespace avk::app
