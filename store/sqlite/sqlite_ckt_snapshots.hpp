#pragma once
// CktSnapshotRepository on SQLite: the ckt_snapshots table.

#include "store/ckt_snapshots.hpp"
#include "store/sqlite.hpp"

namespace avk::store::sqlite {

class SqliteCktSnapshots final : public CktSnapshotRepository {
 public:
  explicit SqliteCktSnapshots(Connection& db) : db_(db) {}

  std::int64_t save(const kinematics::Ckt& table,
                    const std::vector<std::int64_t>& mission_ids) override;
  std::optional<CktSnapshot> latest(const std::string& vehicle_id) override;
  std::int64_t latest_id(const std::string& vehicle_id) override;

 private:
  Connection& db_;
};

}  // namespace avk::store::sqlite
