#include "store/sql/sql_vehicles.hpp"

#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kVehicle = columns("id", "kind", "max_speed_mps", "length_m");

}  // namespace

void insert_vehicle(Database& db, const vehicle::VehicleInfo& info, OnKnownVehicle known) {
  const std::string on_conflict =
      known == OnKnownVehicle::keep
          ? " ON CONFLICT (id) DO NOTHING"
          : " ON CONFLICT (id) DO UPDATE SET kind = excluded.kind, "
            "max_speed_mps = excluded.max_speed_mps, length_m = excluded.length_m";
  auto s = db.prepare("INSERT INTO vehicles (" + kVehicle.list() + ") VALUES (" +
                      kVehicle.placeholders() + ")" + on_conflict);
  s.bind(kVehicle.param("id"), info.id).bind(kVehicle.param("kind"), info.kind);
  s.bind(kVehicle.param("max_speed_mps"), info.max_speed_mps);
  s.bind(kVehicle.param("length_m"), info.length_m);
  s.run();
}

void SqlVehicles::upsert(const vehicle::VehicleInfo& info) {
  insert_vehicle(db_, info, OnKnownVehicle::replace);
}

namespace {

vehicle::VehicleInfo read_vehicle(const Statement& s) {
  return vehicle::VehicleInfo{s.column_text(kVehicle["id"]), s.column_text(kVehicle["kind"]),
                              s.column_double(kVehicle["max_speed_mps"]),
                              s.column_optional_double(kVehicle["length_m"])};
}

}  // namespace

std::optional<vehicle::VehicleInfo> SqlVehicles::get(const std::string& id) {
  auto s = db_.prepare("SELECT " + kVehicle.list() + " FROM vehicles WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_vehicle(s);
}

std::vector<vehicle::VehicleInfo> SqlVehicles::of_kind(const std::string& kind) {
  auto s = db_.prepare("SELECT " + kVehicle.list() + " FROM vehicles WHERE kind = ? ORDER BY id");
  s.bind(1, kind);
  std::vector<vehicle::VehicleInfo> out;
  while (s.step())
    out.push_back(read_vehicle(s));
  return out;
}

}  // namespace avk::store::sql
