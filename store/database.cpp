#include "store/database.hpp"

#include <utility>

namespace avk::store {

const char* to_string(Engine e) {
  return e == Engine::sqlite ? "sqlite" : "postgresql";
}

Statement::Statement(std::unique_ptr<StatementImpl> impl) : impl_(std::move(impl)) {}
Statement::~Statement() = default;
Statement::Statement(Statement&&) noexcept = default;

Statement& Statement::bind(int index, double value) {
  impl_->bind_double(index, value);
  return *this;
}

Statement& Statement::bind(int index, std::int64_t value) {
  impl_->bind_int64(index, value);
  return *this;
}

Statement& Statement::bind(int index, std::string_view text) {
  impl_->bind_text(index, text);
  return *this;
}

Statement& Statement::bind(int index, std::optional<double> value) {
  return value ? bind(index, *value) : bind_null(index, ColumnKind::real);
}

Statement& Statement::bind(int index, std::optional<std::int64_t> value) {
  return value ? bind(index, *value) : bind_null(index, ColumnKind::integer);
}

Statement& Statement::bind(int index, const std::optional<std::string>& value) {
  return value ? bind(index, std::string_view(*value)) : bind_null(index, ColumnKind::text);
}

Statement& Statement::bind_blob(int index, std::span<const unsigned char> bytes) {
  impl_->bind_blob(index, bytes);
  return *this;
}

Statement& Statement::bind_null(int index, ColumnKind kind) {
  impl_->bind_null(index, kind);
  return *this;
}

bool Statement::step() {
  return impl_->step();
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  impl_->reset();
}

int Statement::column_count() const {
  return impl_->column_count();
}
std::string Statement::column_name(int column) const {
  return impl_->column_name(column);
}
ColumnKind Statement::column_kind(int column) const {
  return impl_->column_kind(column);
}
bool Statement::is_null(int column) const {
  return impl_->column_kind(column) == ColumnKind::null;
}
double Statement::column_double(int column) const {
  return impl_->column_double(column);
}
std::int64_t Statement::column_int64(int column) const {
  return impl_->column_int64(column);
}
std::string Statement::column_text(int column) const {
  return impl_->column_text(column);
}

std::optional<double> Statement::column_optional_double(int column) const {
  if (is_null(column)) return std::nullopt;
  return column_double(column);
}

std::optional<std::int64_t> Statement::column_optional_int64(int column) const {
  if (is_null(column)) return std::nullopt;
  return column_int64(column);
}

std::span<const unsigned char> Statement::column_blob(int column) const {
  return impl_->column_blob(column);
}

Transaction::Transaction(Database& db) : db_(db) {
  db_.begin();
}

Transaction::~Transaction() {
  if (!done_) db_.rollback();
}

void Transaction::commit() {
  db_.commit();
  done_ = true;
}

}  // namespace avk::store
