#include "server/http/url.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>

namespace avk::server {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

struct HostPort {
  std::string host;
  std::string port;  // empty: not given
};

// "host", "host:port", "[v6]", "[v6]:port"
std::optional<HostPort> split_host_port(std::string_view authority) {
  if (authority.empty()) return std::nullopt;
  HostPort hp;
  if (authority.front() == '[') {
    const auto close = authority.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    hp.host = lower(authority.substr(0, close + 1));
    const auto rest = authority.substr(close + 1);
    if (!rest.empty()) {
      if (rest.front() != ':') return std::nullopt;
      hp.port = std::string(rest.substr(1));
    }
  } else {
    const auto colon = authority.rfind(':');
    if (colon == std::string_view::npos) {
      hp.host = lower(authority);
    } else {
      hp.host = lower(authority.substr(0, colon));
      hp.port = std::string(authority.substr(colon + 1));
    }
  }
  if (hp.host.empty()) return std::nullopt;
  if (!std::all_of(hp.port.begin(), hp.port.end(),
                   [](unsigned char c) { return std::isdigit(c) != 0; }))
    return std::nullopt;
  return hp;
}

}  // namespace

std::string percent_decode(std::string_view text, bool plus_is_space) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '%' && i + 2 < text.size()) {
      const int hi = hex_value(text[i + 1]);
      const int lo = hex_value(text[i + 2]);
      if (hi >= 0 && lo >= 0) {
        out.push_back(static_cast<char>(hi * 16 + lo));
        i += 2;
        continue;
      }
    }
    out.push_back(plus_is_space && c == '+' ? ' ' : c);
  }
  return out;
}

SplitTarget split_target(std::string_view target) {
  const auto q = target.find('?');
  if (q == std::string_view::npos) return {target, {}};
  return {target.substr(0, q), target.substr(q + 1)};
}

void parse_query(std::string_view raw_query, std::map<std::string, std::string>& query,
                 std::multimap<std::string, std::string>& multi) {
  while (!raw_query.empty()) {
    const auto amp = raw_query.find('&');
    const auto pair = raw_query.substr(0, amp);
    raw_query = amp == std::string_view::npos ? std::string_view{} : raw_query.substr(amp + 1);
    if (pair.empty()) continue;
    const auto eq = pair.find('=');
    std::string key = percent_decode(pair.substr(0, eq), true);
    std::string value =
        eq == std::string_view::npos ? std::string{} : percent_decode(pair.substr(eq + 1), true);
    multi.emplace(key, value);
    query[std::move(key)] = std::move(value);
  }
}

bool origin_allowed(std::string_view origin, std::string_view host,
                    const std::vector<std::string>& allowed_origins) {
  if (same_origin(origin, host)) return true;
  const std::string o = lower(origin);
  return std::find(allowed_origins.begin(), allowed_origins.end(), o) != allowed_origins.end();
}

bool same_origin(std::string_view origin, std::string_view host) {
  const auto sep = origin.find("://");
  if (sep == std::string_view::npos) return false;  // also "null" (sandboxed, file://)
  const std::string scheme = lower(origin.substr(0, sep));
  std::string_view authority = origin.substr(sep + 3);
  authority = authority.substr(0, authority.find('/'));
  const auto o = split_host_port(authority);
  const auto h = split_host_port(host);
  if (!o || !h) return false;
  std::string default_port;
  if (scheme == "http" || scheme == "ws")
    default_port = "80";
  else if (scheme == "https" || scheme == "wss")
    default_port = "443";
  else
    return false;
  const std::string& op = o->port.empty() ? default_port : o->port;
  const std::string& hp = h->port.empty() ? default_port : h->port;
  return o->host == h->host && op == hp;
}

bool is_valid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t n = 0;
    std::uint32_t cp = 0;
    if ((c & 0xE0) == 0xC0) {
      n = 1;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3;
      cp = c & 0x07;
    } else {
      return false;
    }
    if (i + n >= text.size()) return false;
    for (std::size_t k = 1; k <= n; ++k) {
      const auto cc = static_cast<unsigned char>(text[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    static constexpr std::uint32_t kMin[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}

bool host_is_allowed(std::string_view host, const std::vector<std::string>& allowed_names) {
  const auto hp = split_host_port(host);
  if (!hp) return false;
  std::string name = hp->host;
  if (name.size() >= 2 && name.front() == '[') {
    const std::string inner = name.substr(1, name.size() - 2);
    in6_addr v6{};
    return ::inet_pton(AF_INET6, inner.c_str(), &v6) == 1;
  }
  if (!name.empty() && name.back() == '.') name.pop_back();  // "localhost." is localhost
  in_addr v4{};
  if (::inet_pton(AF_INET, name.c_str(), &v4) == 1) return true;
  if (name == "localhost" || name.ends_with(".localhost")) return true;
  return std::any_of(allowed_names.begin(), allowed_names.end(),
                     [&](const std::string& allowed) { return lower(allowed) == name; });
}

bool json_deeper_than(std::string_view text, std::size_t limit) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return true;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return false;
}

}  // namespace avk::server
