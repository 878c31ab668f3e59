#include "app/result.hpp"

namespace avk::app {

std::string_view to_string(ErrorCode c) {
  switch (c) {
    case ErrorCode::not_found:
      return "not_found";
    case ErrorCode::invalid_argument:
      return "invalid_argument";
    case ErrorCode::conflict:
      return "conflict";
    case ErrorCode::not_authorised:
      return "not_authorised";
    case ErrorCode::unsupported:
      return "unsupported";
    case ErrorCode::internal:
      return "internal";
  }
  return "internal";
}

Error not_found(std::string message) {
  return {ErrorCode::not_found, std::move(message), {}, {}, std::nullopt};
}

Error invalid_argument(std::string field, std::string message) {
  return {ErrorCode::invalid_argument, std::move(message), std::move(field), {}, std::nullopt};
}

Error conflict(std::string message, std::optional<std::int64_t> mission_id) {
  return {ErrorCode::conflict, std::move(message), {}, {}, mission_id};
}

Error unsupported(std::string message) {
  return {ErrorCode::unsupported, std::move(message), {}, {}, std::nullopt};
}

Error internal_error(std::string message) {
  return {ErrorCode::internal, std::move(message), {}, {}, std::nullopt};
}

}  // namespace avk::app
