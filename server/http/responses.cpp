#include "server/http/responses.hpp"

#include <nlohmann/json.hpp>

namespace avk::server {

std::string problem_json(unsigned status, std::string_view detail) {
  const auto reason = http::obsolete_reason(http::int_to_status(status));
  return nlohmann::json{{"type", "about:blank"},
                        {"title", std::string(reason.data(), reason.size())},
                        {"status", status},
                        {"detail", std::string(detail)}}
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

http::response<http::string_body> problem_response(http::status status, std::string_view detail,
                                                   unsigned version, bool keep_alive) {
  http::response<http::string_body> res{status, version};
  set_common_headers(res);
  res.set(http::field::content_type, "application/problem+json");
  res.keep_alive(keep_alive);
  res.body() = problem_json(static_cast<unsigned>(status), detail);
  res.prepare_payload();
  return res;
}

http::message_generator body_unless_head(bool head, http::response<http::string_body>&& res) {
  if (!head) return std::move(res);
  http::response<http::empty_body> headers_only(std::move(res.base()));
  return headers_only;
}

}  // namespace avk::server
