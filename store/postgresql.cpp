#include "store/postgresql.hpp"

#include <poll.h>

#include <libpq-fe.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <regex>
#include <vector>

namespace avk::store {

namespace {

// PostgreSQL's type oids (server/catalog/pg_type_d.h, stable across releases).
constexpr Oid kBool = 16, kBytea = 17, kInt8 = 20, kInt2 = 21, kInt4 = 23, kText = 25,
              kFloat4 = 700, kFloat8 = 701, kNumeric = 1700;

void ignore_notice(void*, const char*) {}

// The SQLSTATE of a failed result; empty for an error libpq made itself (a lost connection).
std::string sqlstate(const PGresult* r) {
  const char* s = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  return s ? s : "";
}

// SQLite's parameters ("?" and "?N") as PostgreSQL's ("$N"); a bare "?" takes the number after
// the largest so far, as in SQLite. Quoted text and identifiers are left alone.
std::string renumber_parameters(std::string_view sql, int& count, std::vector<bool>& used) {
  std::string out;
  out.reserve(sql.size() + 16);
  count = 0;
  char quote = 0;
  for (std::size_t i = 0; i < sql.size(); ++i) {
    const char c = sql[i];
    if (quote) {
      if (c == quote) quote = 0;
      out += c;
      continue;
    }
    if (c == '\'' || c == '"') {
      quote = c;
      out += c;
      continue;
    }
    if (c != '?') {
      out += c;
      continue;
    }
    std::size_t j = i + 1;
    while (j < sql.size() && sql[j] >= '0' && sql[j] <= '9')
      ++j;
    int n = count + 1;
    if (j > i + 1) std::from_chars(sql.data() + i + 1, sql.data() + j, n);
    count = std::max(count, n);
    if (used.size() < static_cast<std::size_t>(n)) used.resize(static_cast<std::size_t>(n));
    used[static_cast<std::size_t>(n - 1)] = true;
    out += '$';
    out += std::to_string(n);
    i = j - 1;
  }
  return out;
}

std::string double_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  // The shortest text that reads back as the same double: exact in both directions.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

class PgStatement final : public StatementImpl {
 public:
  PgStatement(const PgConnection& db, std::string_view sql) : db_(&db) {
    int n = 0;
    std::vector<bool> used;
    sql_ = renumber_parameters(sql, n, used);
    values_.resize(static_cast<std::size_t>(n));
    null_.assign(static_cast<std::size_t>(n), true);
    types_.assign(static_cast<std::size_t>(n), 0);
    // A parameter the text never mentions (a statement built without one of its conditions)
    // still needs a type: any will do.
    for (std::size_t i = 0; i < used.size(); ++i)
      if (!used[i]) types_[i] = kText;
    formats_.assign(static_cast<std::size_t>(n), 0);
  }
  ~PgStatement() override { PQclear(res_); }
  PgStatement(const PgStatement&) = delete;
  PgStatement& operator=(const PgStatement&) = delete;

  void bind_double(int index, double value) override { set(index, kFloat8, double_text(value)); }
  void bind_int64(int index, std::int64_t value) override {
    set(index, kInt8, std::to_string(value));
  }
  void bind_text(int index, std::string_view text) override {
    set(index, kText, std::string(text));
  }
  void bind_blob(int index, std::span<const unsigned char> bytes) override {
    // Sent in binary format: the bytes as they are.
    set(index, kBytea, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), 1);
  }
  void bind_null(int index, ColumnKind kind) override {
    const auto i = slot(index);
    null_[i] = true;
    formats_[i] = 0;
    switch (kind) {
      case ColumnKind::integer:
        types_[i] = kInt8;
        break;
      case ColumnKind::real:
        types_[i] = kFloat8;
        break;
      case ColumnKind::text:
        types_[i] = kText;
        break;
      case ColumnKind::blob:
        types_[i] = kBytea;
        break;
      // Left to the server, which infers it from where the parameter stands, unless a value of a
      // known type was bound there before.
      case ColumnKind::null:
        break;
    }
  }

  bool step() override {
    if (!res_) execute();
    ++row_;
    return row_ < PQntuples(res_);
  }
  void reset() override {
    PQclear(res_);
    res_ = nullptr;
    row_ = -1;
    null_.assign(null_.size(), true);
  }

  int column_count() const override { return res_ ? PQnfields(res_) : 0; }
  std::string column_name(int column) const override { return PQfname(res_, column); }
  ColumnKind column_kind(int column) const override {
    if (PQgetisnull(res_, row_, column)) return ColumnKind::null;
    switch (PQftype(res_, column)) {
      case kBool:
      case kInt2:
      case kInt4:
      case kInt8:
        return ColumnKind::integer;
      case kFloat4:
      case kFloat8:
      case kNumeric:
        return ColumnKind::real;
      case kBytea:
        return ColumnKind::blob;
      default:
        return ColumnKind::text;
    }
  }
  double column_double(int column) const override {
    const std::string_view v = value(column);
    double out = 0.0;
    std::from_chars(v.data(), v.data() + v.size(), out);
    return out;
  }
  std::int64_t column_int64(int column) const override {
    const std::string_view v = value(column);
    if (v == "t") return 1;
    if (v == "f") return 0;
    std::int64_t out = 0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
    // A real number read as an integer truncates, as SQLite's conversion does.
    if (r.ptr != v.data() + v.size()) return static_cast<std::int64_t>(column_double(column));
    return out;
  }
  std::string column_text(int column) const override { return std::string(value(column)); }
  std::span<const unsigned char> column_blob(int column) const override {
    if (PQgetisnull(res_, row_, column)) return {};
    std::size_t n = 0;
    const auto* text = reinterpret_cast<const unsigned char*>(PQgetvalue(res_, row_, column));
    std::unique_ptr<unsigned char, decltype(&PQfreemem)> bytes(PQunescapeBytea(text, &n),
                                                               &PQfreemem);
    if (!bytes) throw StoreError("cannot decode a bytea column: out of memory");
    blob_.assign(bytes.get(), bytes.get() + n);
    return blob_;
  }

 private:
  std::size_t slot(int index) const {
    if (index < 1 || index > static_cast<int>(values_.size()))
      throw StoreError("bind: no parameter " + std::to_string(index) + " in \"" + sql_ + "\"");
    return static_cast<std::size_t>(index - 1);
  }
  void set(int index, Oid type, std::string value, int format = 0) {
    const auto i = slot(index);
    values_[i] = std::move(value);
    null_[i] = false;
    types_[i] = type;
    formats_[i] = format;
  }
  std::string_view value(int column) const {
    return {PQgetvalue(res_, row_, column),
            static_cast<std::size_t>(PQgetlength(res_, row_, column))};
  }

  void execute() {
    db_->ensure_open();
    const int n = static_cast<int>(values_.size());
    // A statement run again with the same types on the same session reuses its server-side name
    // without looking it up (the text of a batch insert is long).
    if (prepared_name_.empty() || prepared_types_ != types_ ||
        prepared_session_ != db_->session()) {
      std::string type_key;
      for (const Oid t : types_)
        type_key += std::to_string(t) + ",";
      prepared_name_ = db_->prepared_name(sql_, type_key, types_.data(), n);
      prepared_types_ = types_;
      prepared_session_ = db_->session();
    }
    const std::string& name = prepared_name_;
    std::vector<const char*> values(values_.size());
    std::vector<int> lengths(values_.size());
    for (std::size_t i = 0; i < values_.size(); ++i) {
      values[i] = null_[i] ? nullptr : values_[i].data();
      lengths[i] = static_cast<int>(values_[i].size());
    }
    res_ = PQexecPrepared(db_->handle(), name.c_str(), n, values.data(), lengths.data(),
                          formats_.data(), 0);
    const auto status = PQresultStatus(res_);
    if (status != PGRES_TUPLES_OK && status != PGRES_COMMAND_OK) {
      const std::string message = res_ ? PQresultErrorMessage(res_) : "";
      const std::string state = sqlstate(res_);
      PQclear(res_);
      res_ = nullptr;
      db_->fail("statement failed", message.c_str(), state);
    }
    const char* affected = PQcmdTuples(res_);
    db_->note_changes(*affected ? std::atoi(affected) : 0);
    row_ = -1;
  }

  const PgConnection* db_;
  std::string sql_;
  std::vector<std::string> values_;
  std::vector<bool> null_;
  std::vector<Oid> types_;
  std::vector<int> formats_;
  PGresult* res_ = nullptr;
  int row_ = -1;
  mutable std::vector<unsigned char> blob_;
  std::string prepared_name_;
  std::vector<Oid> prepared_types_;
  std::uint64_t prepared_session_ = 0;
};

// Settings every session of the station uses: doubles printed in their shortest exact form (the
// default since PostgreSQL 12, made explicit), and the server's notices kept out of stderr.
void set_up_session(pg_conn* conn) {
  PQsetNoticeProcessor(conn, ignore_notice, nullptr);
  PQclear(PQexec(conn, "SET extra_float_digits = 3"));
  PQclear(PQexec(conn, "SET client_min_messages = warning"));
}

}  // namespace

bool is_postgresql_target(std::string_view db) {
  return db.starts_with("postgresql://") || db.starts_with("postgres://") ||
         db.find('=') != std::string_view::npos;
}

std::string redacted_target(std::string_view db) {
  static const std::regex uri_password(R"((://[^:/@]*:)[^@]*@)");
  static const std::regex keyword_password(R"((password\s*=\s*)('[^']*'|\S+))");
  std::string out = std::regex_replace(std::string(db), uri_password, "$1***@");
  return std::regex_replace(out, keyword_password, "$1***");
}

PgConnection::PgConnection(const std::string& conninfo) : target_(redacted_target(conninfo)) {
  conn_ = PQconnectdb(conninfo.c_str());
  if (!conn_ || PQstatus(conn_) != CONNECTION_OK) {
    std::string message = conn_ ? PQerrorMessage(conn_) : "out of memory";
    while (!message.empty() && message.back() == '\n')
      message.pop_back();
    PQfinish(conn_);
    conn_ = nullptr;
    throw StoreUnavailable("cannot connect to PostgreSQL '" + target_ + "': " + message);
  }
  set_up_session(conn_);
}

PgConnection::~PgConnection() {
  PQfinish(conn_);
}

void PgConnection::fail(std::string_view what, const char* server_message,
                        const std::string& state) const {
  std::string message = server_message && *server_message ? server_message : PQerrorMessage(conn_);
  while (!message.empty() && message.back() == '\n')
    message.pop_back();
  const std::string text = std::string(what) + ": " + message;
  // The connection is gone when libpq says so, when the error is libpq's own (every error of the
  // server carries an SQLSTATE), or when the server says it is going away or cannot take the
  // session (class 08, and 57P01-57P03: shut down, crashed, starting).
  if (PQstatus(conn_) != CONNECTION_OK || state.empty() || state.starts_with("08") ||
      state == "57P01" || state == "57P02" || state == "57P03") {
    broken_ = true;
    throw StoreUnavailable("PostgreSQL '" + target_ + "' unavailable: " + text);
  }
  throw StoreError(text);
}

void PgConnection::ensure_open() const {
  if (PQstatus(conn_) == CONNECTION_OK && !broken_) return;
  if (in_transaction_)
    throw StoreUnavailable("PostgreSQL '" + target_ + "': connection lost during a transaction");
  PQreset(conn_);
  if (PQstatus(conn_) != CONNECTION_OK) {
    std::string message = PQerrorMessage(conn_);
    while (!message.empty() && message.back() == '\n')
      message.pop_back();
    throw StoreUnavailable("PostgreSQL '" + target_ + "' unavailable: " + message);
  }
  // A new session: statements prepared on the old one are gone, and so are its LISTENs.
  broken_ = false;
  ++session_;
  set_up_session(conn_);
  prepared_.clear();
  reconnected_ = true;
  for (const std::string& channel : channels_) {
    const std::string sql = "LISTEN \"" + channel + "\"";
    PQclear(PQexec(conn_, sql.c_str()));
  }
}

std::string PgConnection::prepared_name(const std::string& sql, const std::string& type_key,
                                        const unsigned* types, int n) const {
  const std::string key = type_key + "|" + sql;
  if (auto it = prepared_.find(key); it != prepared_.end()) return it->second;
  std::string name = "avk_" + std::to_string(prepared_.size() + 1);
  PGresult* r = PQprepare(conn_, name.c_str(), sql.c_str(), n, types);
  const bool ok = PQresultStatus(r) == PGRES_COMMAND_OK;
  const std::string message = r ? PQresultErrorMessage(r) : "";
  const std::string state = sqlstate(r);
  PQclear(r);
  if (!ok) fail("prepare \"" + sql + "\"", message.c_str(), state);
  prepared_.emplace(key, name);
  return name;
}

void PgConnection::exec(const char* sql) {
  ensure_open();
  PGresult* r = PQexec(conn_, sql);
  const auto status = PQresultStatus(r);
  const std::string message = r ? PQresultErrorMessage(r) : "";
  const std::string state = sqlstate(r);
  PQclear(r);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK)
    fail(std::string("SQL failed"), message.c_str(), state);
}

Statement PgConnection::prepare(std::string_view sql) const {
  return Statement(std::make_unique<PgStatement>(*this, sql));
}

void PgConnection::begin() {
  exec("BEGIN");
  in_transaction_ = true;
}

void PgConnection::commit() {
  // Whatever happens, the transaction is over: a failed COMMIT has rolled back (or, when the
  // connection broke, its outcome is unknown and the server will tell at reconnect).
  in_transaction_ = false;
  exec("COMMIT");
}

void PgConnection::rollback() noexcept {
  in_transaction_ = false;
  if (PQstatus(conn_) == CONNECTION_OK && !broken_) PQclear(PQexec(conn_, "ROLLBACK"));
}

void PgConnection::listen(const std::string& channel) {
  exec("LISTEN \"" + channel + "\"");
  channels_.push_back(channel);
}

std::vector<std::string> PgConnection::wait_notification(int timeout_ms) {
  ensure_open();
  std::vector<std::string> out;
  auto drain = [&] {
    if (!PQconsumeInput(conn_)) return;
    while (PGnotify* n = PQnotifies(conn_)) {
      out.emplace_back(n->extra ? n->extra : "");
      PQfreemem(n);
    }
  };
  drain();
  if (!out.empty()) return out;
  pollfd fd{PQsocket(conn_), POLLIN, 0};
  // A dead socket shows as a failed read in drain (PQstatus turns bad); the next call reconnects.
  if (fd.fd >= 0 && ::poll(&fd, 1, timeout_ms) > 0) drain();
  return out;
}

bool PgConnection::take_reconnected() {
  const bool r = reconnected_;
  reconnected_ = false;
  return r;
}

TableChangeListener::TableChangeListener(const std::string& conninfo) : db_(conninfo) {
  db_.listen(kChannel);
}

std::vector<std::string> TableChangeListener::wait(int timeout_ms) {
  try {
    auto changed = db_.wait_notification(timeout_ms);
    if (db_.take_reconnected()) changed.push_back("");
    return changed;
  } catch (const StoreUnavailable&) {
    ::poll(nullptr, 0, timeout_ms);
    return {};
  }
}

}  // namespace avk::store
