#pragma once
// VehicleRepository on SQLite: the vehicles table.

#include "store/sqlite.hpp"
#include "store/vehicles.hpp"

namespace avk::store::sqlite {

// What to do when the vehicle is already stored.
enum class OnKnownVehicle { replace, keep };

// Inside or outside the caller's transaction.
void insert_vehicle(Connection& db, const vehicle::VehicleInfo& info, OnKnownVehicle known);

class SqliteVehicles final : public VehicleRepository {
 public:
  explicit SqliteVehicles(Connection& db) : db_(db) {}

  void upsert(const vehicle::VehicleInfo& info) override;
  std::optional<vehicle::VehicleInfo> get(const std::string& id) override;

 private:
  Connection& db_;
};

}  // namespace avk::store::sqlite
