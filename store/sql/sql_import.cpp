#include "store/sql/sql_import.hpp"

#include <string>
#include <utility>
#include <vector>

#include "kinematics/turn_json.hpp"
#include "store/sql/packed_turns.hpp"
#include "store/sql/sql_currents.hpp"
#include "store/sql/sql_missions.hpp"
#include "store/sql/sql_navigation.hpp"
#include "store/sql/sql_turns.hpp"
#include "store/sql/sql_vehicles.hpp"

namespace avk::store::sql {

std::int64_t import_mission(Database& db, const MissionImport& m) {
  // Everything serialised before the write lock, as a turn is: a document that cannot be
  // written fails before the database is touched.
  std::vector<TurnDocuments> docs;
  docs.reserve(m.turns.size());
  for (const StoredTurn& t : m.turns) {
    std::string raw_json = kinematics::to_json_string(t.raw);
    docs.push_back(t.normalized
                       ? normalized_documents(std::move(raw_json), *t.normalized)
                       : TurnDocuments{std::move(raw_json), std::nullopt, std::nullopt, {}});
  }
  for (const auto& [index, turn] : m.water_turns)
    if (index >= m.turns.size())
      throw StoreError("water-frame turn " + std::to_string(index) + " of " +
                       std::to_string(m.turns.size()) + " turns");

  Transaction tx(db);
  insert_vehicle(db, m.vehicle, OnKnownVehicle::keep);
  const std::int64_t id = SqlMissions::insert(db, m.mission);
  insert_nav(db, id, m.nav);
  SqlMissions missions(db);
  for (const MissionEvent& e : m.events)
    missions.append_event(id, e.t_s, e.kind, e.message);
  for (const ConditionSetTiming& c : m.condition_sets)
    missions.append_condition_set(id, c);
  std::vector<std::int64_t> turn_ids;
  turn_ids.reserve(m.turns.size());
  for (std::size_t i = 0; i < m.turns.size(); ++i)
    turn_ids.push_back(insert_turn(db, id, m.turns[i].row, docs[i]));
  if (m.current) {
    std::vector<PackedWaterTurn> packed;
    for (const auto& [index, turn] : m.water_turns)
      packed.push_back(pack_water_turn(turn_ids[index], turn));
    StoredCurrent c = *m.current;
    c.mission_id = id;
    write_current(db, c, packed);
  }
  tx.commit();
  return id;
}

}  // namespace avk::store::sql
