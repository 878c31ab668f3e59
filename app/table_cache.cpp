#include "app/table_cache.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "app/context.hpp"
#include "app/store_access.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

TableCache::Entry& TableCache::entry(const std::string& vehicle_id, bool include_harvested) {
  std::lock_guard lock(mutex_);
  auto& e = entries_[{vehicle_id, include_harvested}];
  if (!e) e = std::make_unique<Entry>();
  return *e;
}

void TableCache::changed(const std::string& vehicle_id) {
  std::lock_guard lock(generation_mutex_);
  if (vehicle_id.empty())
    ++any_generation_;
  else
    ++vehicle_generation_[vehicle_id];
}

std::pair<std::uint64_t, std::uint64_t> TableCache::generation_of(const std::string& vehicle_id) {
  std::lock_guard lock(generation_mutex_);
  const auto it = vehicle_generation_.find(vehicle_id);
  return {any_generation_, it == vehicle_generation_.end() ? 0 : it->second};
}

void TableCache::forget(const std::string& vehicle_id) {
  for (const bool harvested : {false, true}) {
    Entry& e = entry(vehicle_id, harvested);
    std::lock_guard lock(e.mutex);
    e.value.reset();
  }
  std::lock_guard lock(held_out_mutex_);
  std::erase_if(held_out_, [&](const auto& kv) { return kv.first.vehicle_id == vehicle_id; });
}

const TableCache::Revision& TableCache::revision(Context& ctx, Entry& e,
                                                 const std::string& vehicle_id,
                                                 bool include_harvested, bool stale) {
  const auto now = std::chrono::steady_clock::now();
  // Read before the store: a change announced while the store is read causes another read.
  const auto generation = generation_of(vehicle_id);
  if (!stale && (following_ ? e.generation == generation : now - e.checked < recheck_))
    return e.seen;
  e.checked = now;
  e.generation = generation;
  store::Store& db = store_of(ctx);
  Revision r;
  r.turns = db.turns().newest_ok_id(vehicle_id, include_harvested);
  // A new estimate of a mission's current moves its turns into (or out of) the water frame.
  r.current = r.turns > 0 ? db.currents().revision(vehicle_id) : 0;
  // Only a vehicle without turns is answered by an imported table, so only then is it looked up;
  // its document is read only when the newest id changed.
  r.snapshot = r.turns == 0 ? db.ckt_snapshots().latest_id(vehicle_id) : 0;
  e.seen = r;
  return e.seen;
}

Result<VehicleTable> TableCache::get(Context& ctx, const std::string& vehicle_id,
                                     bool include_harvested) {
  Entry& e = entry(vehicle_id, include_harvested);
  std::lock_guard lock(e.mutex);
  const Revision rev = revision(ctx, e, vehicle_id, include_harvested, !e.value);
  if (e.value && e.value_from == rev) return *e.value;
  store::Store& db = store_of(ctx);
  VehicleTable t;
  t.vehicle_id = vehicle_id;
  t.include_harvested = include_harvested;
  if (rev.turns > 0) {
    // Turns in the water frame where their mission's current is known: the table then predicts
    // through the water, and a query adds the drift of the current it is asked in.
    const auto turns = db.turns().load_normalized({}, vehicle_id, include_harvested,
                                                  store::TurnFrameChoice::water_where_known);
    auto built = std::make_shared<kin::Ckt>(kin::Ckt::build(turns));
    built->vehicle_id = vehicle_id;
    t.speed_changes = std::make_shared<kin::SpeedChangeTable>(kin::SpeedChangeTable::build(turns));
    t.measured_speed_response = kin::measured_speed_response(turns);
    t.table = std::move(built);
    t.source = TableSource::turns;
  } else if (auto snap = rev.snapshot ? db.ckt_snapshots().latest(vehicle_id) : std::nullopt) {
    t.table = std::make_shared<kin::Ckt>(std::move(snap->table));
    t.source = TableSource::imported;
    t.snapshot_id = snap->id;
  } else {
    e.value.reset();
    return not_found("vehicle '" + vehicle_id + "' has no turns and no imported CKT");
  }
  if (t.table->speed_range_mps()) t.fine = std::make_shared<kin::MaterializedCkt>(*t.table);
  e.value_from = rev;
  e.value = t;
  return t;
}

std::shared_ptr<const kin::Ckt> TableCache::held_out(Context& ctx, const std::string& vehicle_id,
                                                     bool include_harvested,
                                                     const store::TurnsLeftOut& left_out) {
  Revision rev;
  {
    Entry& e = entry(vehicle_id, include_harvested);
    std::lock_guard lock(e.mutex);
    rev = revision(ctx, e, vehicle_id, include_harvested, false);
  }
  const HeldOutKey key{vehicle_id, include_harvested, left_out.mission_id, left_out.turn_id};
  {
    std::lock_guard lock(held_out_mutex_);
    const auto it = held_out_.find(key);
    if (it != held_out_.end() && it->second.built_from == rev) {
      it->second.used = ++held_out_uses_;
      return it->second.table;
    }
  }
  // Built outside the lock: two requests for the same new set may both build it, and the
  // second's table replaces the first's (the same turns give the same table).
  const auto turns = store_of(ctx).turns().load_normalized(
      {}, vehicle_id, include_harvested, store::TurnFrameChoice::water_where_known, left_out);
  if (turns.empty()) return nullptr;
  // Kept for queries alone: without the observed turns a table is a fraction of its size.
  auto built = kin::Ckt::build(turns);
  built.drop_observed_turns();
  auto table = std::make_shared<const kin::Ckt>(std::move(built));
  std::lock_guard lock(held_out_mutex_);
  // Tables of an older revision answer no one any more.
  std::erase_if(held_out_, [&](const auto& kv) {
    return kv.first.vehicle_id == vehicle_id && kv.first.include_harvested == include_harvested &&
           kv.second.built_from != rev;
  });
  held_out_[key] = HeldOutTable{rev, table, ++held_out_uses_};
  while (held_out_.size() > kHeldOutTables)
    held_out_.erase(std::min_element(
        held_out_.begin(), held_out_.end(),
        [](const auto& a, const auto& b) { return a.second.used < b.second.used; }));
  return table;
}

}  // namespace avk::app
