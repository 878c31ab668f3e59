#pragma once
// Responses the transport makes itself (errors, static files), in Beast's types: the error body
// is server/http/problem.hpp's, as for the API's own errors, so a client parses one format.

#include <string>
#include <string_view>

#include "server/http/beast.hpp"
#include "server/http/response_generator.hpp"

namespace avk::server {

http::response<http::string_body> problem_response(http::status status, std::string_view detail,
                                                   unsigned version, bool keep_alive);

// The dashboard loads only its own scripts, styles and data; Plotly injects <style> elements and
// draws images from data: and blob: URLs. No page elsewhere may frame it (clickjacking).
inline constexpr std::string_view kContentSecurityPolicy =
    "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data: blob:; connect-src 'self'; object-src 'none'; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'";

// Headers every response carries.
template <class Body>
void set_common_headers(http::response<Body>& res) {
  res.set(http::field::server, "avk-station");
  res.set("X-Content-Type-Options", "nosniff");
  res.set("X-Frame-Options", "DENY");
  res.set("Content-Security-Policy", kContentSecurityPolicy);
  res.set("Referrer-Policy", "no-referrer");
}

// For a HEAD request the same header, Content-Length included, and no body: a body after a
// HEAD answer would be read as the next response on a keep-alive connection. res must be
// prepared (prepare_payload) already.
ResponseGenerator body_unless_head(bool head, http::response<http::string_body>&& res);

}  // namespace avk::server
