#pragma once
// VehicleRepository on either engine: the vehicles table.

#include "store/database.hpp"
#include "store/vehicles.hpp"

namespace avk::store::sql {

// What to do when the vehicle is already stored.
enum class OnKnownVehicle { replace, keep };

// Inside or outside the caller's transaction.
void insert_vehicle(Database& db, const vehicle::VehicleInfo& info, OnKnownVehicle known);

class SqlVehicles final : public VehicleRepository {
 public:
  explicit SqlVehicles(Database& db) : db_(db) {}

  void upsert(const vehicle::VehicleInfo& info) override;
  std::optional<vehicle::VehicleInfo> get(const std::string& id) override;
  std::vector<vehicle::VehicleInfo> of_kind(const std::string& kind) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
