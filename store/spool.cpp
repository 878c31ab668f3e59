#include "store/spool.hpp"

namespace avk::store {

Spool::Spool(const std::string& path) : db_(path) {
  db_.exec("PRAGMA busy_timeout = 5000");
  db_.exec("PRAGMA journal_mode = WAL");
  // FULL: a write counted as spooled is on disk, even if the machine loses power next.
  db_.exec("PRAGMA synchronous = FULL");
  db_.exec(
      "CREATE TABLE IF NOT EXISTS spooled_writes (seq INTEGER PRIMARY KEY, kind TEXT NOT NULL, "
      "mission_id INTEGER NOT NULL, payload TEXT NOT NULL)");
}

std::int64_t Spool::push(const std::string& kind, std::int64_t mission_id,
                         const std::string& payload) {
  auto s = db_.prepare(
      "INSERT INTO spooled_writes (kind, mission_id, payload) VALUES (?, ?, ?) RETURNING seq");
  s.bind(1, kind).bind(2, mission_id).bind(3, payload);
  s.step();
  const std::int64_t seq = s.column_int64(0);
  s.run();
  return seq;
}

std::optional<SpooledWrite> Spool::oldest() {
  auto s =
      db_.prepare("SELECT seq, kind, mission_id, payload FROM spooled_writes ORDER BY seq LIMIT 1");
  if (!s.step()) return std::nullopt;
  return SpooledWrite{s.column_int64(0), s.column_text(1), s.column_int64(2), s.column_text(3)};
}

void Spool::remove(std::int64_t seq) {
  auto s = db_.prepare("DELETE FROM spooled_writes WHERE seq = ?");
  s.bind(1, seq);
  s.run();
}

std::int64_t Spool::count() {
  auto s = db_.prepare("SELECT count(*) FROM spooled_writes");
  s.step();
  return s.column_int64(0);
}

bool Spool::integrity_check() {
  auto s = db_.prepare("PRAGMA integrity_check");
  return s.step() && s.column_text(0) == "ok" && !s.step();
}

}  // namespace avk::store
