#include "store/sql/sql_navigation.hpp"

#include <algorithm>
#include <optional>

#include "store/sql/columns.hpp"

namespace avk::store::sql {

namespace {

constexpr auto kNav = columns("t_s", "x_m", "y_m", "heading_deg", "speed_mps",
                              "desired_heading_deg", "desired_speed_mps", "helm_mode");

// The row's columns start at result column `first` (after the rowid in a page).
NavRow read_nav(const Statement& s, int first) {
  return {s.column_double(first + kNav["t_s"]),
          s.column_double(first + kNav["x_m"]),
          s.column_double(first + kNav["y_m"]),
          s.column_double(first + kNav["heading_deg"]),
          s.column_double(first + kNav["speed_mps"]),
          s.column_optional_double(first + kNav["desired_heading_deg"]),
          s.column_optional_double(first + kNav["desired_speed_mps"]),
          s.column_text(first + kNav["helm_mode"])};
}

}  // namespace

void insert_nav(Database& db, std::int64_t mission_id, std::span<const NavRow> rows) {
  // Up to kRowsPerInsert rows in one statement: a database server is a round trip per
  // statement, and even SQLite parses less.
  constexpr std::size_t kRowsPerInsert = 100;
  constexpr int kParams = 1 + decltype(kNav)::size();
  const auto statement = [&](std::size_t n) {
    std::string values;
    for (std::size_t i = 0; i < n; ++i)
      values += (i ? ", (?, " : "(?, ") + kNav.placeholders() + ")";
    return db.prepare("INSERT INTO nav_samples (mission_id, " + kNav.list() + ") VALUES " + values);
  };
  std::optional<Statement> full;
  for (std::size_t start = 0; start < rows.size(); start += kRowsPerInsert) {
    const std::size_t n = std::min(kRowsPerInsert, rows.size() - start);
    std::optional<Statement> part;
    if (n == kRowsPerInsert && !full) full.emplace(statement(n));
    Statement& s = n == kRowsPerInsert ? *full : part.emplace(statement(n));
    for (std::size_t i = 0; i < n; ++i) {
      const NavRow& r = rows[start + i];
      // The mission is the first parameter of each row; the row's columns follow it.
      const int p = static_cast<int>(i) * kParams + 1;
      s.bind(p, mission_id).bind(p + kNav.param("t_s"), r.t_s).bind(p + kNav.param("x_m"), r.x_m);
      s.bind(p + kNav.param("y_m"), r.y_m).bind(p + kNav.param("heading_deg"), r.heading_deg);
      s.bind(p + kNav.param("speed_mps"), r.speed_mps);
      s.bind(p + kNav.param("desired_heading_deg"), r.desired_heading_deg);
      s.bind(p + kNav.param("desired_speed_mps"), r.desired_speed_mps);
      s.bind(p + kNav.param("helm_mode"), r.helm_mode);
    }
    s.run();
    s.reset();
  }
}

void SqlNavigation::append(std::int64_t mission_id, std::span<const NavRow> rows) {
  Transaction tx(db_);
  insert_nav(db_, mission_id, rows);
  tx.commit();
}

std::vector<NavRow> SqlNavigation::for_mission(std::int64_t mission_id) {
  std::vector<NavRow> out;
  for_each(mission_id, [&](const NavRow& r) { out.push_back(r); });
  return out;
}

void SqlNavigation::for_each(std::int64_t mission_id,
                             const std::function<void(const NavRow&)>& fn) {
  // rowid breaks ties between samples stamped with the same time: insertion order.
  auto s = db_.prepare("SELECT " + kNav.list() +
                       " FROM nav_samples WHERE mission_id = ? ORDER BY t_s, rowid");
  s.bind(1, mission_id);
  while (s.step())
    fn(read_nav(s, 0));
}

std::int64_t SqlNavigation::count(std::int64_t mission_id) {
  auto s = db_.prepare("SELECT COUNT(*) FROM nav_samples WHERE mission_id = ?");
  s.bind(1, mission_id);
  return s.step() ? s.column_int64(0) : 0;
}

std::vector<NavPageRow> SqlNavigation::page(std::int64_t mission_id, std::int64_t after_rowid,
                                            int limit) {
  auto s = db_.prepare("SELECT rowid, " + kNav.list() +
                       " FROM nav_samples WHERE mission_id = ? AND rowid > ? "
                       "ORDER BY rowid LIMIT ?");
  s.bind(1, mission_id).bind(2, after_rowid).bind(3, limit);
  std::vector<NavPageRow> out;
  while (s.step())
    out.push_back({s.column_int64(0), read_nav(s, 1)});
  return out;
}

std::optional<NavPageRow> SqlNavigation::last(std::int64_t mission_id) {
  // Walks the (mission_id, t_s) index from its end: one row read, however long the mission.
  auto s = db_.prepare("SELECT rowid, " + kNav.list() +
                       " FROM nav_samples WHERE mission_id = ? ORDER BY t_s DESC, rowid DESC "
                       "LIMIT 1");
  s.bind(1, mission_id);
  if (!s.step()) return std::nullopt;
  return NavPageRow{s.column_int64(0), read_nav(s, 1)};
}

}  // namespace avk::store::sql
