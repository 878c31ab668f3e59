#pragma once
// NavigationRepository on either engine: the nav_samples table.

#include "store/database.hpp"
#include "store/navigation.hpp"

namespace avk::store::sql {

// Inside the caller's transaction, one prepared statement for the whole batch.
void insert_nav(Database& db, std::int64_t mission_id, std::span<const NavRow> rows);

class SqlNavigation final : public NavigationRepository {
 public:
  explicit SqlNavigation(Database& db) : db_(db) {}

  void append(std::int64_t mission_id, std::span<const NavRow> rows) override;
  std::vector<NavRow> for_mission(std::int64_t mission_id) override;
  void for_each(std::int64_t mission_id, const std::function<void(const NavRow&)>& fn) override;
  std::int64_t count(std::int64_t mission_id) override;
  std::vector<NavPageRow> page(std::int64_t mission_id, std::int64_t after_rowid,
                               int limit) override;
  std::optional<NavPageRow> last(std::int64_t mission_id) override;

 private:
  Database& db_;
};

}  // namespace avk::store::sql
