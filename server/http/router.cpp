#include "server/http/router.hpp"

#include "server/http/bearer_token.hpp"
#include "server/http/problem.hpp"

namespace avk::server {

namespace {

std::vector<std::string> segments(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : path) {
    if (c == '/') {
      if (!cur.empty()) out.push_back(std::move(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(std::move(cur));
  return out;
}

bool matches(const std::vector<std::string>& pattern, const std::vector<std::string>& path,
             PathParams& params) {
  if (pattern.size() != path.size()) return false;
  PathParams found;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const std::string& p = pattern[i];
    if (p.size() > 2 && p.front() == '{' && p.back() == '}')
      found[p.substr(1, p.size() - 2)] = path[i];
    else if (p != path[i])
      return false;
  }
  params = std::move(found);
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
  routes_.push_back(std::move(route));
}

Router::Match Router::match(const ApiRequest& request) const {
  const auto path = segments(request.path);
  // A HEAD is the GET without its body.
  const std::string method = request.method == "HEAD" ? "GET" : request.method;
  Match m;
  for (const Route& r : routes_) {
    PathParams params;
    if (!matches(segments(r.pattern), path, params)) continue;
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
  if (access == Access::read && request.remote_is_loopback) return true;
  return bearer_token_matches(request.authorization, token_);
}

std::optional<ApiResponse> Router::refusal(const ApiRequest& request, Access access) const {
  if (authorised(request, access)) return std::nullopt;
  return unauthorised(request);
}

Admission Router::admit(const ApiRequest& head) {
  Admission a;
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
