#pragma once
// What a use case answers: a value, or an error of a closed set that each front end maps once
// (HTTP status and problem+json; CLI message and exit code). Errors are values, not exception
// types, so no front end has to guess from a type what went wrong.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace avk::app {

enum class ErrorCode {
  not_found,         // the named vehicle, mission, turn, model or table does not exist
  invalid_argument,  // a parameter or document field is wrong (Error::field names it)
  conflict,          // the station's state forbids it now (a mission running, not connected)
  not_authorised,    // the caller may not do this
  unsupported,       // understood, but this data cannot answer it (no guided navigation, ...)
  internal,          // a fault of the station (a corrupt stored document, SQLite)
};

std::string_view to_string(ErrorCode c);

// One problem of a document, e.g. a mission file: its field (a JSON pointer) and what is wrong.
struct FieldError {
  std::string field;
  std::string message;
};

struct Error {
  ErrorCode code = ErrorCode::internal;
  std::string message;
  // The offending parameter: a query/option name ("speed"), or a JSON pointer ("/missions") for
  // a field of a request document.
  std::string field;
  std::vector<FieldError> fields;          // every problem, when a document has several
  std::optional<std::int64_t> mission_id;  // a conflict: the mission in the way
};

Error not_found(std::string message);
Error invalid_argument(std::string field, std::string message);
Error conflict(std::string message, std::optional<std::int64_t> mission_id = std::nullopt);
Error unsupported(std::string message);
Error internal_error(std::string message);

// A value or an Error, in the manner of C++23's std::expected.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::in_place_index<0>, std::move(value)) {}
  Result(Error error) : v_(std::in_place_index<1>, std::move(error)) {}

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

// For a use case with nothing to return but its outcome.
struct Done {};
using Status = Result<Done>;

}  // namespace avk::app
