#pragma once
// HarvestRepository on either engine: the harvests table.

#include "store/database.hpp"
#include "store/harvests.hpp"

namespace avk::store::sql {

class SqlHarvests final : public HarvestRepository {
 public:
  explicit SqlHarvests(Database& db) : db_(db) {}

  std::int64_t save(const HarvestRecord& h) override;
  std::vector<HarvestRecord> list(std::int64_t mission_id) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
