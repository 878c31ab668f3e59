#pragma once
// CktSnapshotRepository on either engine: the ckt_snapshots table.

#include "store/ckt_snapshots.hpp"
#include "store/database.hpp"

namespace avk::store::sql {

class SqlCktSnapshots final : public CktSnapshotRepository {
 public:
  explicit SqlCktSnapshots(Database& db) : db_(db) {}

  std::int64_t save(const kinematics::Ckt& table,
                    const std::vector<std::int64_t>& mission_ids) override;
  std::optional<CktSnapshot> latest(const std::string& vehicle_id) override;
  std::int64_t latest_id(const std::string& vehicle_id) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
