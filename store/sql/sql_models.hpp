#pragma once
// ModelRepository on either engine: the yaw_models table.

#include "store/database.hpp"
#include "store/models.hpp"

namespace avk::store::sql {

class SqlModels final : public ModelRepository {
 public:
  explicit SqlModels(Database& db) : db_(db) {}

  std::int64_t save(const StoredModel& m) override;
  std::optional<StoredModel> get(std::int64_t id) override;
  std::vector<StoredModel> list(const std::optional<std::string>& vehicle_id) override;
  std::optional<StoredModel> latest(const std::optional<std::string>& vehicle_id) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
