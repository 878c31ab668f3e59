#include "app/ckt_tables.hpp"

#include <cmath>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <string>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "app/table_cache.hpp"
#include "app/utc_time.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/number_text.hpp"
#include "kinematics/text_limit.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

const char* to_string(TableSource s) {
  return s == TableSource::turns ? "turns" : "imported";
}

Result<VehicleTable> vehicle_table(Context& ctx, const std::string& vehicle_id,
                                   bool include_harvested) {
  return ctx.tables().get(ctx, vehicle_id, include_harvested);
}

Result<VehicleTable> class_table(Context& ctx, const std::string& vehicle_id,
                                 bool include_harvested) {
  store::Store& db = store_of(ctx);
  const auto info = db.vehicles().get(vehicle_id);
  if (!info) return not_found("no vehicle '" + vehicle_id + "' in the database");
  VehicleTable t;
  t.vehicle_id = vehicle_id;
  t.include_harvested = include_harvested;
  std::vector<kin::TurnSequence> turns;
  for (const auto& v : db.vehicles().of_kind(info->kind)) {
    auto own = db.turns().load_normalized({}, v.id, include_harvested,
                                          store::TurnFrameChoice::water_where_known);
    if (own.empty()) continue;
    t.pooled_vehicles.push_back(v.id);
    turns.insert(turns.end(), std::make_move_iterator(own.begin()),
                 std::make_move_iterator(own.end()));
  }
  if (turns.empty()) return not_found("no vehicle of class '" + info->kind + "' has turns");
  auto built = std::make_shared<kin::Ckt>(kin::Ckt::build(turns));
  built->vehicle_id = vehicle_id;
  t.speed_changes = std::make_shared<kin::SpeedChangeTable>(kin::SpeedChangeTable::build(turns));
  t.measured_speed_response = kin::measured_speed_response(turns);
  t.table = std::move(built);
  if (t.table->speed_range_mps()) t.fine = std::make_shared<kin::MaterializedCkt>(*t.table);
  return t;
}

Result<SidedCell> ckt_cell(Context& ctx, const std::string& vehicle_id, double speed_mps,
                           double dheading_deg, bool include_harvested) {
  auto t = vehicle_table(ctx, vehicle_id, include_harvested);
  if (!t) return t.error();
  const auto si = t->table->speed_index(speed_mps);
  const auto di = t->table->dheading_index(std::abs(dheading_deg));
  if (!si || !di)
    return not_found("no cell at " + kin::number_text(speed_mps) + " m/s, " +
                     kin::number_text(dheading_deg) + " deg in the table");
  SidedCell out;
  out.cell = t->table->cell(*si, *di);
  out.side = kin::side_of(dheading_deg);
  out.dheading_deg =
      out.side == kin::TurnSide::left ? -out.cell.dheading_deg : out.cell.dheading_deg;
  const auto sided = [port = out.side == kin::TurnSide::left](kin::Polyline line) {
    return port ? kin::reflect_x(std::move(line)) : line;
  };
  for (const auto& tr : out.cell.turns)
    out.turns.push_back(sided(tr.points()));
  out.mean_turn = sided(out.cell.mean_turn);
  out.trajectory = sided(out.cell.trajectory);
  if (out.cell.fit.domain_max > out.cell.fit.domain_min)
    out.fit = sided(out.cell.fit.sample(kFitSampleStepM));
  return out;
}

Result<kin::Ckt> ckt_for_export(Context& ctx, const std::string& vehicle_id,
                                bool include_harvested) {
  auto t = vehicle_table(ctx, vehicle_id, include_harvested);
  if (!t) return t.error();
  kin::Ckt out = *t->table;
  out.vehicle_id = vehicle_id;
  return out;
}

Result<ImportedTable> import_ckt(Context& ctx, const std::string& vehicle_id,
                                 const std::string& ckt_file_text) {
  if (const auto why = vehicle::vehicle_id_problem(vehicle_id))
    return invalid_argument("vehicle_id", "the vehicle id " + *why);
  kin::Ckt t;
  try {
    t = kin::parse_ckt_json(ckt_file_text);
  } catch (const std::exception& e) {
    return invalid_argument("", std::string("not a CKT file: ") + e.what());
  }
  if (t.vehicle_id != vehicle_id)
    return invalid_argument("vehicle_id", "the file's table is for vehicle '" + t.vehicle_id +
                                              "', not '" + vehicle_id + "'");
  if (const auto why = kin::text_too_long(t.created_utc, kMaxCreatedUtcBytes))
    return invalid_argument("created_utc", "the file's created_utc " + *why);
  const auto id = store_of(ctx).ckt_snapshots().save(t, {});
  ctx.tables().forget(vehicle_id);
  return ImportedTable{id, vehicle_id};
}

Result<BuiltTable> build_ckt(Context& ctx, const std::string& vehicle_id,
                             const std::vector<std::int64_t>& missions,
                             const kin::CktOptions& options, std::optional<double> vehicle_length_m,
                             bool include_harvested) {
  store::Store& db = store_of(ctx);
  for (const auto id : missions)
    if (!db.missions().get(id)) return not_found("no mission " + std::to_string(id));
  const auto turns = db.turns().load_normalized(missions, vehicle_id, include_harvested,
                                                store::TurnFrameChoice::water_where_known);
  if (turns.empty()) return not_found("no ok turns of '" + vehicle_id + "' to build from");
  BuiltTable out;
  out.harvested_turns = static_cast<std::size_t>(std::count_if(
      turns.begin(), turns.end(),
      [](const kin::TurnSequence& t) { return t.meta().source == kin::TurnSource::harvested; }));
  out.table = kin::Ckt::build(turns, options, std::nullopt, &out.report);
  out.table.vehicle_id = vehicle_id;
  out.table.vehicle_length_m = vehicle_length_m;
  out.table.created_utc = utc_now_iso8601();
  out.snapshot_id = db.ckt_snapshots().save(out.table, missions);
  return out;
}

}  // namespace avk::app
