#pragma once
// RFC 9457 problem+json, the one error format of the station's HTTP answers, whether the
// transport refuses a request or a handler does. Building one never throws: a detail quoting
// what a client sent (a path, a parameter) may hold anything, invalid UTF-8 included.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "server/api_types.hpp"

namespace avk::server {

// {"type":"about:blank","title":<the status' reason phrase>,"status":..,"detail":..} plus the
// members of extra (an object; anything else is ignored).
std::string problem_json(int status, std::string_view detail,
                         const nlohmann::json& extra = nlohmann::json::object()) noexcept;

// The same as an API response (content type application/problem+json).
ApiResponse problem_response(int status, std::string_view detail,
                             const nlohmann::json& extra = nlohmann::json::object()) noexcept;

}  // namespace avk::server
