#include "server/http/problem.hpp"

#include "server/http/beast.hpp"

namespace avk::server {

std::string problem_json(int status, std::string_view detail,
                         const nlohmann::json& extra) noexcept {
  try {
    const auto reason = http::obsolete_reason(http::int_to_status(static_cast<unsigned>(status)));
    nlohmann::json j = {{"type", "about:blank"},
                        {"title", std::string(reason.data(), reason.size())},
                        {"status", status},
                        {"detail", std::string(detail)}};
    if (extra.is_object())
      for (const auto& [k, v] : extra.items())
        if (!j.contains(k)) j[k] = v;
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (...) {
    // Only an allocation can fail above; the answer stays well-formed without the detail.
    return R"({"type":"about:blank","title":"Internal Server Error","status":500})";
  }
}

ApiResponse problem_response(int status, std::string_view detail,
                             const nlohmann::json& extra) noexcept {
  ApiResponse r;
  r.status = status;
  r.content_type = "application/problem+json";
  r.body = problem_json(status, detail, extra);
  return r;
}

}  // namespace avk::server
