#include "server/http/router.hpp"

#include <algorithm>
#include <string_view>

#include "server/http/bearer_token.hpp"
#include "server/http/problem.hpp"

namespace avk::server {

namespace {

// Views into the path: splitting allocates nothing but the vector.
std::vector<std::string_view> segments(std::string_view path) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (end > start) out.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

bool is_param(std::string_view segment) {
  return segment.size() > 2 && segment.front() == '{' && segment.back() == '}';
}

// Literal segments first: most routes fail there, before anything is captured.
bool matches(const std::vector<std::string>& pattern, const std::vector<std::string_view>& path,
             PathParams& params) {
  if (pattern.size() != path.size()) return false;
  for (std::size_t i = 0; i < pattern.size(); ++i)
    if (!is_param(pattern[i]) && pattern[i] != path[i]) return false;
  params.clear();
  for (std::size_t i = 0; i < pattern.size(); ++i)
    if (is_param(pattern[i]))
      params[pattern[i].substr(1, pattern[i].size() - 2)] = std::string(path[i]);
  return true;
}

ApiResponse unauthorised(const ApiRequest& r) {
  ApiResponse res = problem_response(401, r.authorization.empty()
                                              ? "this endpoint needs the station's bearer token"
                                              : "the bearer token is not the station's");
  res.headers.push_back({"WWW-Authenticate", "Bearer"});
  return res;
}

}  // namespace

void Router::add(Route route) {
  std::vector<std::string> pattern;
  for (const auto segment : segments(route.pattern))
    pattern.emplace_back(segment);
  patterns_.push_back(std::move(pattern));
  if (route.method == "GET" && (route.access == Access::control || route.body_limit_bytes))
    gets_are_open_reads_ = false;
  routes_.push_back(std::move(route));
}

Router::Match Router::match(const ApiRequest& request) const {
  const auto path = segments(request.path);
  // A HEAD is the GET without its body.
  const std::string method = request.method == "HEAD" ? "GET" : request.method;
  Match m;
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    const Route& r = routes_[i];
    PathParams params;
    if (!matches(patterns_[i], path, params)) continue;
    if (r.method == method) {
      m.route = &r;
      m.params = std::move(params);
      return m;
    }
    if (m.allow.find(r.method) == std::string::npos)
      m.allow += (m.allow.empty() ? "" : ", ") + r.method;
  }
  return m;
}

bool Router::authorised(const ApiRequest& request, Access access) const {
  if (access != Access::control && request.remote_is_loopback) return true;
  if (bearer_token_matches(request.authorization, token_)) return true;
  if (access != Access::image) return false;
  const auto it = request.query.find("token");
  return it != request.query.end() && bearer_token_matches("Bearer " + it->second, token_);
}

std::optional<ApiResponse> Router::refusal(const ApiRequest& request, Access access) const {
  if (authorised(request, access)) return std::nullopt;
  return unauthorised(request);
}

Admission Router::admit(const ApiRequest& head) {
  Admission a;
  const bool read = head.method == "GET" || head.method == "HEAD";
  if (read && head.remote_is_loopback && gets_are_open_reads_) return a;
  const Match m = match(head);
  // Not a route: only the token's holder learns that, on the body-less 404 after.
  a.refusal = refusal(head, m.route ? m.route->access : Access::read);
  if (m.route) a.body_limit_bytes = m.route->body_limit_bytes;
  return a;
}

bool Router::may_open_stream(const ApiRequest& request) {
  return authorised(request, Access::read);
}

ApiResponse Router::handle(const ApiRequest& request) {
  const Match m = match(request);
  if (auto no = refusal(request, m.route ? m.route->access : Access::read)) return *no;
  if (!m.route) {
    if (m.allow.empty()) return problem_response(404, "no resource at " + request.path);
    ApiResponse res = problem_response(405, request.method + " is not allowed on " + request.path,
                                       {{"allow", m.allow}});
    res.headers.push_back({"Allow", m.allow});
    return res;
  }
  try {
    return m.route->handler(request, m.params);
  } catch (const RequestError& e) {
    return problem_response(e.status(), e.what(), e.extra());
  } catch (const std::exception& e) {
    // The log has the library's words; the transport tells the client only that it failed.
    return ApiResponse{500, "", e.what(), {}};
  }
}

}  // namespace avk::server
