#pragma once
// The URL pieces the transport takes apart: request targets, query strings and Origin headers.
// Kept free of Beast so they stay plain string functions.

#include <map>
#include <string>
#include <string_view>

namespace avk::server {

// %XX sequences decoded; a malformed one is kept as it came (handlers validate what they get).
// In a query, '+' is a space (HTML forms); in a path it is a plus.
std::string percent_decode(std::string_view text, bool plus_is_space);

struct SplitTarget {
  std::string_view path;   // raw, still encoded
  std::string_view query;  // raw, without the '?'
};
SplitTarget split_target(std::string_view target);

// Every value of a repeated key goes to multi; query keeps the last one.
void parse_query(std::string_view raw_query, std::map<std::string, std::string>& query,
                 std::multimap<std::string, std::string>& multi);

// Whether an Origin header ("scheme://host[:port]") names the host:port of the Host header.
// A missing port is the scheme's default on both sides, so a proxy that drops it still matches.
bool same_origin(std::string_view origin, std::string_view host);

}  // namespace avk::server
