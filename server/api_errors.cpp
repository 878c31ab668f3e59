#include "server/api_errors.hpp"

#include <nlohmann/json.hpp>

#include "server/http/problem.hpp"

namespace avk::server {

ApiResponse problem_of(const app::Error& e, bool document) {
  using app::ErrorCode;
  nlohmann::json extra = nlohmann::json::object();
  std::string detail = e.message;
  int status = 500;
  switch (e.code) {
    case ErrorCode::not_found:
      status = 404;
      break;
    case ErrorCode::invalid_argument:
      status = document ? 422 : 400;
      if (!e.field.empty()) {
        if (document) {
          // A field is a JSON pointer, with or without its leading '/'.
          const std::string pointer = e.field.front() == '/' ? e.field : "/" + e.field;
          extra["pointer"] = pointer;
          detail = pointer + ": " + e.message;
        } else if (e.fields.size() > 1) {
          // Several parameters at once (predict's speed and heading change): each named.
          extra["parameter"] = e.field;
          detail.clear();
          for (const auto& f : e.fields) {
            if (!detail.empty()) detail += "; ";
            detail += "parameter '" + f.field + "': " + f.message;
          }
        } else {
          extra["parameter"] = e.field;
          detail = "parameter '" + e.field + "': " + e.message;
        }
      }
      break;
    case ErrorCode::conflict:
      status = 409;
      break;
    case ErrorCode::not_authorised:
      status = 403;
      break;
    case ErrorCode::unsupported:
      status = 422;
      break;
    case ErrorCode::internal:
      // The transport logs the message and tells the client only that the station failed.
      return ApiResponse{500, "", e.message, {}};
  }
  if (!e.fields.empty()) {
    nlohmann::json errors = nlohmann::json::array();
    for (const auto& f : e.fields)
      errors.push_back({{"field", f.field}, {"message", f.message}});
    extra["errors"] = std::move(errors);
  }
  if (e.mission_id) extra["mission_id"] = *e.mission_id;
  return problem_response(status, detail, extra);
}

}  // namespace avk::server
