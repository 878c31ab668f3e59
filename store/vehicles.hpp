#pragma once
// The vehicles the station knows: what a mission is flown with.

#include <optional>
#include <string>

#include <vector>
#include "store/store_error.hpp"

#include "vehicle/vehicle.hpp"

namespace avk::store {

class VehicleRepository {
 public:
  virtual ~VehicleRepository() = default;

  // Inserts the vehicle or replaces what is known of it.
  virtual void upsert(const vehicle::VehicleInfo& info) = 0;
  virtual std::optional<vehicle::VehicleInfo> get(const std::string& id) = 0;
  // Every vehicle of the kind (a vehicle class: "catamaran:m200"), by id.
  virtual std::vector<vehicle::VehicleInfo> of_kind(const std::string& kind) = 0;
};

}  // namespace avk::store
