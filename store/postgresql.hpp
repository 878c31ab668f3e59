#pragma once
// The PostgreSQL engine over libpq: one connection for one thread. Statements are prepared on the
// server once per connection and text-format values carry doubles exactly (shortest round-trip
// form both ways). A broken connection is reopened at the next statement outside a transaction
// (libpq tries every host of a multi-host connection string in turn, so a promoted standby is
// found); until then every call throws StoreUnavailable.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "store/database.hpp"

struct pg_conn;

namespace avk::store {

// True when `db` names a PostgreSQL database rather than an SQLite file: a postgresql:// or
// postgres:// URI, or a libpq keyword/value string ("service=lab", "host=... dbname=...").
bool is_postgresql_target(std::string_view db);

// `db` with any password replaced by "***", for messages and logs.
std::string redacted_target(std::string_view db);

class PgConnection final : public Database {
 public:
  // Throws StoreUnavailable naming the target (without its password) when it cannot connect.
  explicit PgConnection(const std::string& conninfo);
  ~PgConnection() override;
  PgConnection(const PgConnection&) = delete;
  PgConnection& operator=(const PgConnection&) = delete;

  Engine engine() const override { return Engine::postgresql; }
  using Database::exec;
  void exec(const char* sql) override;
  Statement prepare(std::string_view sql) const override;
  int changes() const override { return changes_; }
  void begin() override;
  void commit() override;
  void rollback() noexcept override;
  const char* now_utc_sql() const override {
    return "to_char(now() AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"')";
  }
  std::string json_integers_sql(std::string_view param) const override {
    return "SELECT json_array_elements_text(CAST(" + std::string(param) + " AS json))::bigint";
  }

  // LISTEN on `channel`; then wait_notification returns the payloads that arrived, waiting up to
  // timeout_ms for the first. An empty result after a reconnect means notifications may have
  // been missed: the caller must treat everything as changed (reconnected() says so once).
  void listen(const std::string& channel);
  std::vector<std::string> wait_notification(int timeout_ms);
  bool take_reconnected();

  // Internal to the engine's statements.
  pg_conn* handle() const { return conn_; }
  // Reopens a broken connection (outside a transaction); throws StoreUnavailable.
  void ensure_open() const;
  // The server-side name of `sql` prepared for `types`, preparing it on first use.
  std::string prepared_name(const std::string& sql, const std::string& type_key,
                            const unsigned* types, int n) const;
  void note_changes(int n) const { changes_ = n; }
  // Counts the sessions this connection has had: statements prepared in an earlier one are gone.
  std::uint64_t session() const { return session_; }
  // Throws StoreUnavailable when the connection is gone (the next statement reopens it), else
  // StoreError with the server's text. state: the error's SQLSTATE, empty for libpq's own.
  [[noreturn]] void fail(std::string_view what, const char* server_message,
                         const std::string& state) const;

 private:
  std::string target_;  // redacted, for messages
  pg_conn* conn_ = nullptr;
  mutable std::map<std::string, std::string> prepared_;
  mutable int changes_ = 0;
  mutable bool in_transaction_ = false;
  mutable bool reconnected_ = false;
  mutable bool broken_ = false;
  mutable std::uint64_t session_ = 1;  // a failure said the connection is gone, whatever libpq says
  std::vector<std::string> channels_;
};

// What other stations change in a shared database, as the triggers of schema 13 announce it on
// channel avk_table_change: the vehicle whose table may have changed with every turn, table
// snapshot, model or current written.
class TableChangeListener {
 public:
  // Connects and listens; throws StoreUnavailable when the server cannot be reached.
  explicit TableChangeListener(const std::string& conninfo);
  // Waits up to timeout_ms for changes; the vehicles they name ("" for a row without one). After
  // the connection was lost and reopened it returns {""} once (notifications may have been
  // missed). While the server cannot be reached it waits timeout_ms and returns nothing.
  std::vector<std::string> wait(int timeout_ms);
  static constexpr const char* kChannel = "avk_table_change";

 private:
  PgConnection db_;
};

}  // namespace avk::store
