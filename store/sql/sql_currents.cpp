#include "store/sql/sql_currents.hpp"

#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kCurrent = columns(
    "mission_id", "t_s", "method", "east_mps", "north_mps", "cov_ee", "cov_en", "cov_nn",
    "speed_scale", "residual_rms_mps", "evidence", "revision", "reference_legs",
    "rms_over_ground_mps", "rms_through_water_mps", "reference_separation_mps", "speed_reference",
    "drift_legs", "drift_along_mps", "drift_cross_mps", "drift_mean_leg_s");

// The current as the "c" of a query that may join the mission.
std::string select_currents() {
  return "SELECT " + kCurrent.list("c.") + " FROM mission_currents c ";
}

// The currents of the vehicle's missions (parameter 1), in the given order.
std::string select_vehicle_currents(std::string_view order) {
  return select_currents() + "JOIN missions m ON m.id = c.mission_id WHERE m.vehicle_id = ? " +
         std::string(order);
}

StoredCurrent read_current(const Statement& s) {
  StoredCurrent c;
  c.mission_id = s.column_int64(kCurrent["mission_id"]);
  c.t_s = s.column_double(kCurrent["t_s"]);
  c.method = s.column_text(kCurrent["method"]);
  c.estimate.east_mps = s.column_double(kCurrent["east_mps"]);
  c.estimate.north_mps = s.column_double(kCurrent["north_mps"]);
  c.estimate.covariance = {s.column_double(kCurrent["cov_ee"]), s.column_double(kCurrent["cov_en"]),
                           s.column_double(kCurrent["cov_nn"])};
  c.estimate.speed_scale = s.column_double(kCurrent["speed_scale"]);
  c.estimate.residual_rms_mps = s.column_double(kCurrent["residual_rms_mps"]);
  c.estimate.legs = static_cast<std::size_t>(s.column_int64(kCurrent["evidence"]));
  c.revision = s.column_int64(kCurrent["revision"]);
  if (!s.is_null(kCurrent["reference_legs"])) {
    kinematics::SpeedReferenceEvidence r;
    r.legs = static_cast<std::size_t>(s.column_int64(kCurrent["reference_legs"]));
    r.rms_over_ground_mps = s.column_double(kCurrent["rms_over_ground_mps"]);
    r.rms_through_water_mps = s.column_double(kCurrent["rms_through_water_mps"]);
    r.separation_mps = s.column_double(kCurrent["reference_separation_mps"]);
    if (!s.is_null(kCurrent["speed_reference"]))
      r.identified = parse_stored("mission " + std::to_string(c.mission_id), "speed reference",
                                  s.column_text(kCurrent["speed_reference"]),
                                  kinematics::parse_speed_reference);
    c.speed_reference = r;
  }
  if (!s.is_null(kCurrent["drift_legs"]))
    c.drift_scatter = kinematics::DriftScatter{
        s.column_double(kCurrent["drift_along_mps"]), s.column_double(kCurrent["drift_cross_mps"]),
        static_cast<std::size_t>(s.column_int64(kCurrent["drift_legs"])),
        s.column_double(kCurrent["drift_mean_leg_s"])};
  return c;
}

void bind_current(Statement& s, const StoredCurrent& current, std::int64_t revision) {
  const kinematics::CurrentEstimate& e = current.estimate;
  s.bind(kCurrent.param("mission_id"), current.mission_id);
  s.bind(kCurrent.param("t_s"), current.t_s).bind(kCurrent.param("method"), current.method);
  s.bind(kCurrent.param("east_mps"), e.east_mps).bind(kCurrent.param("north_mps"), e.north_mps);
  s.bind(kCurrent.param("cov_ee"), e.covariance[0]);
  s.bind(kCurrent.param("cov_en"), e.covariance[1]);
  s.bind(kCurrent.param("cov_nn"), e.covariance[2]);
  s.bind(kCurrent.param("speed_scale"), e.speed_scale);
  s.bind(kCurrent.param("residual_rms_mps"), e.residual_rms_mps);
  s.bind(kCurrent.param("evidence"), static_cast<std::int64_t>(e.legs));
  s.bind(kCurrent.param("revision"), revision);
  // The evidence columns, from reference_legs to the end of the list, stay NULL where not
  // evaluated.
  for (int i = kCurrent.param("reference_legs"); i <= kCurrent.size(); ++i)
    s.bind_null(i);
  if (const auto& r = current.speed_reference) {
    s.bind(kCurrent.param("reference_legs"), static_cast<std::int64_t>(r->legs));
    s.bind(kCurrent.param("rms_over_ground_mps"), r->rms_over_ground_mps);
    s.bind(kCurrent.param("rms_through_water_mps"), r->rms_through_water_mps);
    s.bind(kCurrent.param("reference_separation_mps"), r->separation_mps);
    if (r->identified)
      s.bind(kCurrent.param("speed_reference"), kinematics::to_string(*r->identified));
  }
  if (const auto& d = current.drift_scatter) {
    s.bind(kCurrent.param("drift_legs"), static_cast<std::int64_t>(d->legs));
    s.bind(kCurrent.param("drift_along_mps"), d->along_mps);
    s.bind(kCurrent.param("drift_cross_mps"), d->cross_mps);
    s.bind(kCurrent.param("drift_mean_leg_s"), d->mean_leg_s);
  }
}

}  // namespace

std::int64_t write_current(Database& db, const StoredCurrent& current,
                           const std::vector<PackedWaterTurn>& packed) {
  auto rev = db.prepare("SELECT coalesce(max(revision), 0) + 1 FROM mission_currents");
  rev.step();
  const std::int64_t revision = rev.column_int64(0);
  // A mission has one current: a new estimate replaces the row.
  auto s = db.prepare("INSERT INTO mission_currents (" + kCurrent.list() + ") VALUES (" +
                      kCurrent.placeholders() + ") ON CONFLICT (mission_id) DO UPDATE SET " +
                      kCurrent.set_from_excluded() + ", estimated_utc = " + db.now_utc_sql());
  bind_current(s, current, revision);
  s.run();
  auto clear = db.prepare(
      "UPDATE turns SET water_samples = NULL, water_meta_json = NULL WHERE mission_id = ?");
  clear.bind(1, current.mission_id);
  clear.run();
  auto put = db.prepare(
      "UPDATE turns SET water_meta_json = ?, water_samples = ? WHERE id = ? AND mission_id = ?");
  for (const auto& [id, meta, samples] : packed) {
    put.bind(1, meta).bind_blob(2, samples).bind(3, id).bind(4, current.mission_id);
    put.run();
    if (db.changes() != 1)
      throw StoreError("turn " + std::to_string(id) + " is not a turn of mission " +
                       std::to_string(current.mission_id));
    put.reset();
  }
  return revision;
}

std::int64_t SqlCurrents::save(
    const StoredCurrent& current,
    const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& water_turns) {
  // Serialised before the write lock, as a turn is.
  std::vector<PackedWaterTurn> packed;
  packed.reserve(water_turns.size());
  for (const auto& [id, turn] : water_turns)
    packed.push_back(pack_water_turn(id, turn));
  Transaction tx(db_);
  const std::int64_t revision = write_current(db_, current, packed);
  tx.commit();
  return revision;
}

std::optional<StoredCurrent> SqlCurrents::for_mission(std::int64_t mission_id) {
  auto s = db_.prepare(select_currents() + "WHERE c.mission_id = ?");
  s.bind(1, mission_id);
  if (!s.step()) return std::nullopt;
  return read_current(s);
}

std::optional<StoredCurrent> SqlCurrents::latest_for_vehicle(const std::string& vehicle_id) {
  auto s = db_.prepare(select_vehicle_currents("ORDER BY c.revision DESC LIMIT 1"));
  s.bind(1, vehicle_id);
  if (!s.step()) return std::nullopt;
  return read_current(s);
}

std::vector<StoredCurrent> SqlCurrents::for_vehicle(const std::string& vehicle_id) {
  auto s = db_.prepare(select_vehicle_currents("ORDER BY c.revision"));
  s.bind(1, vehicle_id);
  std::vector<StoredCurrent> out;
  while (s.step())
    out.push_back(read_current(s));
  return out;
}

std::int64_t SqlCurrents::revision(const std::string& vehicle_id) {
  auto s = db_.prepare(
      "SELECT coalesce(max(c.revision), 0) FROM mission_currents c JOIN missions m ON "
      "m.id = c.mission_id WHERE m.vehicle_id = ?");
  s.bind(1, vehicle_id);
  s.step();
  return s.column_int64(0);
}

}  // namespace avk::store::sql
