#include "store/db_copy.hpp"

#include <string_view>

namespace avk::store {

namespace {

struct CopiedTable {
  const char* name;
  const char* key;       // the order rows are copied in, which keeps ids and navigation order
  bool key_is_identity;  // the database numbers the key (a vehicle's id is its name)
};

// Parents before children, so that every foreign key finds its row.
constexpr CopiedTable kTables[] = {
    {"vehicles", "id", false},      {"missions", "id", true},
    {"nav_samples", "rowid", true}, {"condition_sets", "id", true},
    {"mission_events", "id", true}, {"turns", "id", true},
    {"harvests", "id", true},       {"mission_currents", "mission_id", false},
    {"yaw_models", "id", true},     {"ckt_snapshots", "id", true},
};

std::int64_t count_rows(Database& db, const CopiedTable& t) {
  auto s = db.prepare(std::string("SELECT count(*) FROM ") + t.name);
  s.step();
  return s.column_int64(0);
}

std::string select_all(const Database& db, const CopiedTable& t) {
  // SQLite's rowid is not among "*"; PostgreSQL's navigation table has it as a column.
  const bool rowid_hidden = db.engine() == Engine::sqlite && std::string_view(t.key) == "rowid";
  return std::string("SELECT ") + (rowid_hidden ? "rowid AS rowid, " : "") + "* FROM " + t.name +
         " ORDER BY " + t.key;
}

void bind_value(Statement& to, int param, const Statement& from, int column) {
  switch (from.column_kind(column)) {
    case ColumnKind::integer:
      to.bind(param, from.column_int64(column));
      break;
    case ColumnKind::real:
      to.bind(param, from.column_double(column));
      break;
    case ColumnKind::text:
      to.bind(param, from.column_text(column));
      break;
    case ColumnKind::blob:
      to.bind_blob(param, from.column_blob(column));
      break;
    case ColumnKind::null:
      to.bind_null(param);
      break;
  }
}

std::int64_t copy_table(Database& from, Database& to, const CopiedTable& t) {
  auto rows = from.prepare(select_all(from, t));
  std::optional<Statement> insert;
  std::int64_t n = 0;
  while (rows.step()) {
    if (!insert) {
      std::string columns, params;
      for (int c = 0; c < rows.column_count(); ++c) {
        columns += (c ? ", " : "") + rows.column_name(c);
        params += c ? ", ?" : "?";
      }
      insert.emplace(to.prepare(std::string("INSERT INTO ") + t.name + " (" + columns +
                                ") VALUES (" + params + ")"));
    }
    for (int c = 0; c < rows.column_count(); ++c)
      bind_value(*insert, c + 1, rows, c);
    insert->run();
    insert->reset();
    ++n;
  }
  // PostgreSQL's identity columns do not follow explicit ids: the next id must come after the
  // copied ones.
  if (to.engine() == Engine::postgresql && n > 0 && t.key_is_identity)
    to.exec(std::string("SELECT setval(pg_get_serial_sequence('") + t.name + "', '" + t.key +
            "'), (SELECT max(" + t.key + ") FROM " + t.name + "))");
  return n;
}

}  // namespace

std::vector<TableCount> copy_database(Store& from, Store& to) {
  Database& src = from.database();
  Database& dst = to.database();
  // One consistent view of the source while other stations may write to it.
  Transaction read(src);
  if (src.engine() == Engine::postgresql)
    src.exec("SET TRANSACTION ISOLATION LEVEL REPEATABLE READ");
  Transaction write(dst);
  for (const CopiedTable& t : kTables)
    if (const auto n = count_rows(dst, t); n != 0)
      throw StoreError("the target already holds " + std::to_string(n) + " rows of " + t.name +
                       ": copy into an empty database");
  std::vector<TableCount> counts;
  for (const CopiedTable& t : kTables) {
    const std::int64_t copied = copy_table(src, dst, t);
    const std::int64_t in_source = count_rows(src, t);
    const std::int64_t in_target = count_rows(dst, t);
    if (copied != in_source || in_target != in_source)
      throw StoreError(std::string("copy of ") + t.name +
                       " is incomplete: " + std::to_string(in_source) + " rows in the source, " +
                       std::to_string(copied) + " copied, " + std::to_string(in_target) +
                       " in the target");
    counts.push_back({t.name, copied});
  }
  write.commit();
  return counts;
}

}  // namespace avk::store
