#include "server/http/router.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
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

ApiResponse method_not_allowed(const ApiRequest& r, const std::string& allow) {
  ApiResponse res =
      problem_response(405, r.method + " is not allowed on " + r.path, {{"allow", allow}});
  res.headers.push_back({"Allow", allow});
  return res;
}

std::string lower_trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  std::string out(s);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// One media range of an Accept header: "text/*;q=0.5" -> {"text/*", 0.5}.
struct MediaRange {
  std::string range;
  double q = 1.0;
};

std::vector<MediaRange> media_ranges(std::string_view accept) {
  std::vector<MediaRange> out;
  while (!accept.empty()) {
    const std::size_t comma = std::min(accept.find(','), accept.size());
    std::string_view item = accept.substr(0, comma);
    accept.remove_prefix(std::min(comma + 1, accept.size()));
    const std::size_t semi = std::min(item.find(';'), item.size());
    MediaRange m{lower_trimmed(item.substr(0, semi)), 1.0};
    if (m.range.empty()) continue;
    std::string_view params = item.substr(semi);
    while (!params.empty()) {
      params.remove_prefix(1);  // the ';'
      const std::size_t next = std::min(params.find(';'), params.size());
      const std::string param = lower_trimmed(params.substr(0, next));
      params.remove_prefix(next);
      if (param.rfind("q=", 0) == 0) {
        char* end = nullptr;
        const double q = std::strtod(param.c_str() + 2, &end);
        // A malformed weight is read as the default rather than as a refusal of the type.
        if (end != param.c_str() + 2 && q >= 0.0 && q <= 1.0) m.q = q;
      }
    }
    out.push_back(std::move(m));
  }
  return out;
}

// 3 for type/subtype, 2 for type/*, 1 for */*, 0 when the range does not cover the type.
int specificity(const std::string& range, const std::string& type) {
  if (range == type) return 3;
  if (range == "*/*") return 1;
  const std::size_t slash = type.find('/');
  if (range.size() == slash + 2 && range.ends_with("/*") &&
      range.compare(0, slash, type, 0, slash) == 0)
    return 2;
  return 0;
}

}  // namespace

const Representation& choose_representation(const ApiRequest& request,
                                            const std::vector<Representation>& offered) {
  if (const auto it = request.query.find("format"); it != request.query.end()) {
    for (const auto& r : offered)
      if (r.format == it->second) return r;
    std::string names;
    for (std::size_t i = 0; i < offered.size(); ++i) {
      if (i > 0) names += i + 1 == offered.size() ? " or " : ", ";
      names += offered[i].format;
    }
    std::string detail = "parameter 'format': must be ";
    detail += names;
    throw RequestError(400, detail, {{"parameter", "format"}});
  }
  if (request.accept.empty()) return offered.front();
  const auto ranges = media_ranges(request.accept);
  const Representation* best = nullptr;
  double best_q = 0.0;
  int best_specificity = 0;
  for (const auto& r : offered) {
    // The most specific range covering the type decides its weight (RFC 9110 12.5.1).
    int spec = 0;
    double q = 0.0;
    for (const auto& m : ranges) {
      const int s = specificity(m.range, r.media_type);
      if (s > spec) {
        spec = s;
        q = m.q;
      }
    }
    if (q > best_q || (q == best_q && q > 0.0 && spec > best_specificity)) {
      best = &r;
      best_q = q;
      best_specificity = spec;
    }
  }
  if (best) return *best;
  nlohmann::json acceptable = nlohmann::json::array();
  std::string types;
  for (std::size_t i = 0; i < offered.size(); ++i) {
    acceptable.push_back(offered[i].media_type);
    if (i > 0) types += i + 1 == offered.size() ? " and " : ", ";
    types += offered[i].media_type;
  }
  std::string detail = "this resource is available as ";
  detail += types;
  detail += "; Accept: '";
  detail += request.accept.substr(0, 80);
  detail += "' allows none of them";
  throw RequestError(406, detail, {{"acceptable", acceptable}});
}

void Router::add(Route route, RouteCost cost) {
  std::vector<std::string> pattern;
  for (const auto segment : segments(route.pattern))
    pattern.emplace_back(segment);
  patterns_.push_back(std::move(pattern));
  routes_.push_back(std::move(route));
  costs_.push_back(std::move(cost));
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
  const Match m = match(head);
  // A method the path does not take is refused as such before the token is asked for: no
  // token would make it succeed, and the route table is public (docs/api.md).
  if (!m.route && !m.allow.empty()) {
    a.refusal = method_not_allowed(head, m.allow);
    return a;
  }
  // Not a route: only the token's holder learns that, on the body-less 404 after.
  a.refusal = refusal(head, m.route ? m.route->access : Access::read);
  if (!m.route) return a;
  a.body_limit_bytes = m.route->body_limit_bytes;
  const RouteCost& cost = costs_[static_cast<std::size_t>(m.route - routes_.data())];
  a.workload = cost.workload;
  if (a.workload == Workload::cheap &&
      std::ranges::any_of(cost.expensive_with,
                          [&](const std::string& name) { return head.query.contains(name); }))
    a.workload = Workload::expensive;
  return a;
}

bool Router::may_open_stream(const ApiRequest& request) {
  return authorised(request, Access::read);
}

ApiResponse Router::handle(const ApiRequest& request) {
  const Match m = match(request);
  if (!m.route && !m.allow.empty()) return method_not_allowed(request, m.allow);
  if (auto no = refusal(request, m.route ? m.route->access : Access::read)) return *no;
  if (!m.route) return problem_response(404, "no resource at " + request.path);
  try {
    // Content negotiation is the route table's, so that every route refuses alike.
    choose_representation(request, m.route->representations);
    return m.route->handler(request, m.params);
  } catch (const RequestError& e) {
    return problem_response(e.status(), e.what(), e.extra());
  } catch (const std::exception& e) {
    // The log has the library's words; the transport tells the client only that it failed.
    return ApiResponse{500, "", e.what(), {}};
  }
}

}  // namespace avk::server
