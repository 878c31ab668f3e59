#include "store/sqlite.hpp"

#include <sqlite3.h>

#include <memory>

namespace avk::store {

Connection::Connection(const std::string& path) {
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX;
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    // sqlite3_open_v2 hands back a handle even on failure, and it must be closed.
    const std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError("cannot open database '" + path + "': " + msg, rc);
  }
  sqlite3_extended_result_codes(db_, 1);
}

Connection::~Connection() {
  // Statements are owned by RAII objects that die first, so close cannot be left busy.
  sqlite3_close(db_);
}

void Connection::check(int rc, std::string_view what) const {
  if (rc == SQLITE_OK || rc == SQLITE_ROW || rc == SQLITE_DONE) return;
  throw StoreError(
      std::string(what) + ": " + sqlite3_errmsg(db_) + " (code " + std::to_string(rc) + ")", rc);
}

void Connection::exec(const char* sql) {
  char* err = nullptr;
  const int rc = sqlite3_exec(db_, sql, nullptr, nullptr, &err);
  if (rc != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errstr(rc);
    sqlite3_free(err);
    throw StoreError(std::string("SQL failed: ") + msg + " (code " + std::to_string(rc) + ")", rc);
  }
}

namespace {

class SqliteStatement final : public StatementImpl {
 public:
  SqliteStatement(const Connection& db, std::string_view sql) : db_(&db) {
    const int rc =
        sqlite3_prepare_v2(db.handle(), sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr);
    db.check(rc, "prepare");
  }
  ~SqliteStatement() override { sqlite3_finalize(stmt_); }
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  void bind_double(int index, double value) override {
    db_->check(sqlite3_bind_double(stmt_, index, value), "bind");
  }
  void bind_int64(int index, std::int64_t value) override {
    db_->check(sqlite3_bind_int64(stmt_, index, value), "bind");
  }
  void bind_text(int index, std::string_view text) override {
    // SQLITE_TRANSIENT: SQLite copies, so temporaries passed in are safe.
    db_->check(
        sqlite3_bind_text64(stmt_, index, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8),
        "bind");
  }
  void bind_blob(int index, std::span<const unsigned char> bytes) override {
    // A zero-length blob from a null pointer would bind NULL; "" keeps it an empty blob.
    static const unsigned char kEmpty = 0;
    const void* data = bytes.empty() ? &kEmpty : bytes.data();
    db_->check(sqlite3_bind_blob64(stmt_, index, data, bytes.size(), SQLITE_TRANSIENT), "bind");
  }
  void bind_null(int index, ColumnKind) override {
    db_->check(sqlite3_bind_null(stmt_, index), "bind");
  }

  bool step() override {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    // Reset so the statement does not keep a half-finished write open after the error.
    sqlite3_reset(stmt_);
    db_->check(rc, "step");
    return false;
  }
  void reset() override {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }

  int column_count() const override { return sqlite3_column_count(stmt_); }
  std::string column_name(int column) const override {
    const char* name = sqlite3_column_name(stmt_, column);
    return name ? name : "";
  }
  ColumnKind column_kind(int column) const override {
    switch (sqlite3_column_type(stmt_, column)) {
      case SQLITE_INTEGER:
        return ColumnKind::integer;
      case SQLITE_FLOAT:
        return ColumnKind::real;
      case SQLITE_TEXT:
        return ColumnKind::text;
      case SQLITE_BLOB:
        return ColumnKind::blob;
      default:
        return ColumnKind::null;
    }
  }
  double column_double(int column) const override { return sqlite3_column_double(stmt_, column); }
  std::int64_t column_int64(int column) const override {
    return sqlite3_column_int64(stmt_, column);
  }
  std::string column_text(int column) const override {
    const auto* p = sqlite3_column_text(stmt_, column);
    const int n = sqlite3_column_bytes(stmt_, column);
    return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(n))
             : std::string();
  }
  std::span<const unsigned char> column_blob(int column) const override {
    // sqlite3_column_blob before sqlite3_column_bytes: the documented order that avoids a
    // conversion invalidating the pointer.
    const auto* p = static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, column));
    const int n = sqlite3_column_bytes(stmt_, column);
    if (!p) return {};
    return {p, static_cast<std::size_t>(n)};
  }

 private:
  const Connection* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

Statement Connection::prepare(std::string_view sql) const {
  return Statement(std::make_unique<SqliteStatement>(*this, sql));
}

std::int64_t Connection::last_insert_rowid() const {
  return sqlite3_last_insert_rowid(db_);
}
int Connection::changes() const {
  return sqlite3_changes(db_);
}

void Connection::begin() {
  exec("BEGIN IMMEDIATE");
}

void Connection::commit() {
  exec("COMMIT");
}

void Connection::rollback() noexcept {
  sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

}  // namespace avk::store
