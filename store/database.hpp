#pragma once
// One connection to one of the store's engines (SQLite or PostgreSQL), as the repositories see
// it: prepared statements with bound parameters, a transaction guard, and the few expressions the
// two dialects spell differently. Values never enter SQL text; only fixed statements written in
// store/ are prepared. Statement text uses SQLite's parameters ("?" and "?N"); the PostgreSQL
// engine renumbers them to "$N".

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "store/store_error.hpp"

namespace avk::store {

enum class Engine { sqlite, postgresql };
const char* to_string(Engine e);

// The storage class of a result value, for code that copies rows it does not know the shape of.
enum class ColumnKind { null, integer, real, text, blob };

// What an engine implements behind a Statement. Parameters are 1-based, columns 0-based.
class StatementImpl {
 public:
  virtual ~StatementImpl() = default;
  virtual void bind_double(int index, double value) = 0;
  virtual void bind_int64(int index, std::int64_t value) = 0;
  virtual void bind_text(int index, std::string_view text) = 0;
  virtual void bind_blob(int index, std::span<const unsigned char> bytes) = 0;
  // A NULL of the given kind: PostgreSQL must know a parameter's type where the statement does
  // not tell it ("? IS NULL"); ColumnKind::null leaves it to the statement.
  virtual void bind_null(int index, ColumnKind kind) = 0;
  virtual bool step() = 0;
  virtual void reset() = 0;
  virtual int column_count() const = 0;
  virtual std::string column_name(int column) const = 0;
  virtual ColumnKind column_kind(int column) const = 0;
  virtual double column_double(int column) const = 0;
  virtual std::int64_t column_int64(int column) const = 0;
  virtual std::string column_text(int column) const = 0;
  virtual std::span<const unsigned char> column_blob(int column) const = 0;
};

class Statement {
 public:
  explicit Statement(std::unique_ptr<StatementImpl> impl);
  ~Statement();
  Statement(Statement&&) noexcept;
  Statement& operator=(Statement&&) = delete;

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
  Statement& bind(int index, const std::optional<std::string>& value);
  Statement& bind_blob(int index, std::span<const unsigned char> bytes);
  Statement& bind_null(int index, ColumnKind kind = ColumnKind::null);

  // True while a row is available; false when done. Throws StoreError on failure.
  bool step();
  // Runs a statement that returns no rows.
  void run();
  // Makes the statement ready for new bindings (keeps the compiled form, which is the point).
  void reset();

  int column_count() const;
  std::string column_name(int column) const;
  ColumnKind column_kind(int column) const;
  bool is_null(int column) const;
  double column_double(int column) const;
  std::int64_t column_int64(int column) const;
  std::string column_text(int column) const;
  std::optional<double> column_optional_double(int column) const;
  std::optional<std::int64_t> column_optional_int64(int column) const;
  // Valid until the next step, reset or column access on this statement; empty for NULL.
  std::span<const unsigned char> column_blob(int column) const;

 private:
  std::unique_ptr<StatementImpl> impl_;
};

class Database {
 public:
  virtual ~Database() = default;
  virtual Engine engine() const = 0;

  // For fixed statements without parameters (DDL, settings).
  virtual void exec(const char* sql) = 0;
  void exec(const std::string& sql) { exec(sql.c_str()); }
  virtual Statement prepare(std::string_view sql) const = 0;
  // Rows changed by the last INSERT, UPDATE or DELETE.
  virtual int changes() const = 0;

  // A write transaction: the write lock is taken at begin, so a busy writer waits there instead
  // of failing halfway through.
  virtual void begin() = 0;
  virtual void commit() = 0;
  // Never throws: a failed rollback leaves the engine to discard the work when the connection
  // closes.
  virtual void rollback() noexcept = 0;

  // The current moment as ISO 8601 UTC text with milliseconds ("2026-12-08T10:00:00.123Z"),
  // as an SQL expression.
  virtual const char* now_utc_sql() const = 0;
  // A subquery of the integers of the JSON array (text) bound at `param` ("?2"), for IN (...).
  virtual std::string json_integers_sql(std::string_view param) const = 0;
};

// Rolls back unless committed.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace avk::store
