#pragma once
// A thin RAII layer over the sqlite3 C API: one connection, prepared statements with bound
// parameters, and a transaction guard that rolls back unless committed. Values never enter SQL
// text; only fixed statements written in store/ are prepared.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "store/store_error.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace avk::store {

class Statement;

class Connection {
 public:
  explicit Connection(const std::string& path);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // For fixed statements without parameters (pragmas, DDL, BEGIN/COMMIT).
  void exec(const char* sql);
  Statement prepare(std::string_view sql);
  std::int64_t last_insert_rowid() const;
  int changes() const;
  sqlite3* handle() const { return db_; }

  // Throws StoreError naming what was being done, with SQLite's message, when rc is an error.
  void check(int rc, std::string_view what) const;

 private:
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(const Connection& db, std::string_view sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&&) = delete;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Parameters are 1-based, as in SQLite.
  Statement& bind(int index, double value);
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, std::string_view text);
  Statement& bind(int index, const char* text) { return bind(index, std::string_view(text)); }
  Statement& bind(int index, const std::string& text) {
    return bind(index, std::string_view(text));
  }
  Statement& bind(int index, std::optional<double> value);
  Statement& bind(int index, std::optional<std::int64_t> value);
  Statement& bind_blob(int index, std::span<const unsigned char> bytes);
  Statement& bind_null(int index);

  // True while a row is available; false when done. Throws StoreError on failure.
  bool step();
  // Runs a statement that returns no rows.
  void run();
  // Makes the statement ready for new bindings (keeps the compiled form, which is the point).
  void reset();

  bool is_null(int column) const;
  double column_double(int column) const;
  std::int64_t column_int64(int column) const;
  std::string column_text(int column) const;
  std::optional<double> column_optional_double(int column) const;
  std::optional<std::int64_t> column_optional_int64(int column) const;
  // Valid until the next step, reset or column access on this statement; empty for NULL.
  std::span<const unsigned char> column_blob(int column) const;

 private:
  const Connection* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE takes the write lock up front, so a busy writer waits (busy_timeout) at the
// start instead of failing halfway through with SQLITE_BUSY on lock upgrade.
class Transaction {
 public:
  explicit Transaction(Connection& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Connection& db_;
  bool done_ = false;
};

}  // namespace avk::store
