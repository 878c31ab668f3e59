#pragma once
// HarvestRepository on SQLite: the harvests table.

#include "store/harvests.hpp"
#include "store/sqlite.hpp"

namespace avk::store::sqlite {

class SqliteHarvests final : public HarvestRepository {
 public:
  explicit SqliteHarvests(Connection& db) : db_(db) {}

  std::int64_t save(const HarvestRecord& h) override;
  std::vector<HarvestRecord> list(std::int64_t mission_id) override;

 private:
  Connection& db_;
};

}  // namespace avk::store::sqlite
