#pragma once
// Responses the transport makes itself (errors, static files): RFC 9457 problem+json, the same
// shape the API handlers use, so a client parses one error format.

#include <string>
#include <string_view>

#include "server/http/beast.hpp"

namespace avk::server {

std::string problem_json(unsigned status, std::string_view detail);

http::response<http::string_body> problem_response(http::status status, std::string_view detail,
                                                   unsigned version, bool keep_alive);

// Headers every response carries.
template <class Body>
void set_common_headers(http::response<Body>& res) {
  res.set(http::field::server, "avk-station");
  res.set("X-Content-Type-Options", "nosniff");
}

}  // namespace avk::server
