#pragma once
// ModelRepository on SQLite: the yaw_models table.

#include "store/models.hpp"
#include "store/sqlite.hpp"

namespace avk::store::sqlite {

class SqliteModels final : public ModelRepository {
 public:
  explicit SqliteModels(Connection& db) : db_(db) {}

  std::int64_t save(const StoredModel& m) override;
  std::optional<StoredModel> get(std::int64_t id) override;
  std::vector<StoredModel> list(const std::optional<std::string>& vehicle_id) override;
  std::optional<StoredModel> latest(const std::optional<std::string>& vehicle_id) override;

 private:
  Connection& db_;
};

}  // namespace avk::store::sqlite
