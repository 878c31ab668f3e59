#pragma once
// A vehicle's Cached Kinematics Table as the station answers with it: built from the vehicle's
// own ok turns (in the water frame where their mission's current is known, app/current.hpp), or,
// when it has none, its latest imported table. One rule for every front end.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/result.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/speed_change_table.hpp"
#include "kinematics/speed_response.hpp"

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
  // A vehicle class's pooled table (class_table): every vehicle whose turns it holds.
  std::vector<std::string> pooled_vehicles;
};

// The vehicle's table (not_found when it has no turns and no imported table). Built from its
// collection turns, and its harvested turns too when include_harvested.
Result<VehicleTable> vehicle_table(Context& ctx, const std::string& vehicle_id,
                                   bool include_harvested = false);

// The table of the vehicle's class: the ok turns of every stored vehicle of the same kind
// (vehicles of one class on one station or several stations sharing a database), pooled on
// request, as the thesis' table of one hull serves its sister hulls. Built on each call, not
// cached. not_found for an unknown vehicle or a class without turns.
Result<VehicleTable> class_table(Context& ctx, const std::string& vehicle_id,
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
