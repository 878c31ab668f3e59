#include "store/sql/sql_ckt_snapshots.hpp"

#include <exception>

#include <nlohmann/json.hpp>

#include "kinematics/ckt_file.hpp"
#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kSnapshot = columns("id", "created_utc", "mission_ids", "document");

CktSnapshot read_snapshot(const Statement& s) {
  CktSnapshot snap;
  snap.id = s.column_int64(kSnapshot["id"]);
  snap.created_utc = s.column_text(kSnapshot["created_utc"]);
  snap.document = s.column_text(kSnapshot["document"]);
  try {
    snap.mission_ids = nlohmann::json::parse(s.column_text(kSnapshot["mission_ids"]))
                           .get<std::vector<std::int64_t>>();
    snap.table = kinematics::parse_ckt_json(snap.document);
  } catch (const std::exception& e) {
    throw StoreError("CKT snapshot " + std::to_string(snap.id) + " is corrupt: " + e.what());
  }
  return snap;
}

}  // namespace

std::int64_t SqlCktSnapshots::save(const kinematics::Ckt& table,
                                   const std::vector<std::int64_t>& mission_ids) {
  const std::string ids = nlohmann::json(mission_ids).dump();
  const std::string doc = kinematics::ckt_to_json_string(table);
  auto s = db_.prepare(
      "INSERT INTO ckt_snapshots (mission_ids, document, vehicle_id) VALUES (?, ?, ?) RETURNING "
      "id");
  s.bind(1, ids).bind(2, doc).bind(3, table.vehicle_id);
  return inserted_id(s);
}

std::int64_t SqlCktSnapshots::latest_id(const std::string& vehicle_id) {
  auto s = db_.prepare("SELECT coalesce(max(id), 0) FROM ckt_snapshots WHERE vehicle_id = ?");
  s.bind(1, vehicle_id);
  s.step();
  return s.column_int64(0);
}

std::optional<CktSnapshot> SqlCktSnapshots::latest(const std::string& vehicle_id) {
  auto s = db_.prepare("SELECT " + kSnapshot.list() +
                       " FROM ckt_snapshots WHERE vehicle_id = ? ORDER BY id DESC LIMIT 1");
  s.bind(1, vehicle_id);
  if (!s.step()) return std::nullopt;
  return read_snapshot(s);
}

}  // namespace avk::store::sql
