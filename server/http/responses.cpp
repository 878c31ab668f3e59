#include "server/http/responses.hpp"

#include "server/http/problem.hpp"

namespace avk::server {

http::response<http::string_body> problem_response(http::status status, std::string_view detail,
                                                   unsigned version, bool keep_alive) {
  http::response<http::string_body> res{status, version};
  set_common_headers(res);
  res.set(http::field::content_type, "application/problem+json");
  res.keep_alive(keep_alive);
  res.body() = problem_json(static_cast<int>(status), detail);
  res.prepare_payload();
  return res;
}

ResponseGenerator body_unless_head(bool head, http::response<http::string_body>&& res) {
  if (!head) return std::move(res);
  http::response<http::empty_body> headers_only(std::move(res.base()));
  return headers_only;
}

}  // namespace avk::server
