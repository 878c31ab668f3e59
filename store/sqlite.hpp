#pragma once
// The SQLite engine: a thin RAII layer over the sqlite3 C API, one connection for one thread.
// Tests and the tile reader also open a file with it directly for raw SQL.

#include <cstdint>
#include <string>
#include <string_view>

#include "store/database.hpp"

struct sqlite3;

namespace avk::store {

class Connection final : public Database {
 public:
  explicit Connection(const std::string& path);
  ~Connection() override;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  Engine engine() const override { return Engine::sqlite; }
  using Database::exec;
  void exec(const char* sql) override;
  Statement prepare(std::string_view sql) const override;
  int changes() const override;
  // BEGIN IMMEDIATE takes the write lock up front, so a busy writer waits (busy_timeout) at the
  // start instead of failing halfway through with SQLITE_BUSY on lock upgrade.
  void begin() override;
  void commit() override;
  void rollback() noexcept override;
  const char* now_utc_sql() const override { return "strftime('%Y-%m-%dT%H:%M:%fZ', 'now')"; }
  std::string json_integers_sql(std::string_view param) const override {
    return "SELECT value FROM json_each(" + std::string(param) + ")";
  }

  std::int64_t last_insert_rowid() const;
  sqlite3* handle() const { return db_; }

  // Throws StoreError naming what was being done, with SQLite's message, when rc is an error.
  void check(int rc, std::string_view what) const;

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace avk::store
