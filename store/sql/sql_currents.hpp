#pragma once
// CurrentRepository on either engine: the mission_currents table and the water-frame columns of
// turns.

#include "store/currents.hpp"
#include "store/database.hpp"
#include "store/sql/packed_turns.hpp"

namespace avk::store::sql {

// Replaces the mission's current and the water-frame form of its turns, inside the caller's
// transaction; the new revision.
std::int64_t write_current(Database& db, const StoredCurrent& current,
                           const std::vector<PackedWaterTurn>& packed);

class SqlCurrents final : public CurrentRepository {
 public:
  explicit SqlCurrents(Database& db) : db_(db) {}

  std::int64_t save(
      const StoredCurrent& current,
      const std::vector<std::pair<std::int64_t, kinematics::TurnSequence>>& water_turns) override;
  std::optional<StoredCurrent> for_mission(std::int64_t mission_id) override;
  std::optional<StoredCurrent> latest_for_vehicle(const std::string& vehicle_id) override;
  std::vector<StoredCurrent> for_vehicle(const std::string& vehicle_id) override;
  std::int64_t revision(const std::string& vehicle_id) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
