#pragma once
// The URL pieces the transport takes apart: request targets, query strings and Origin headers.
// Kept free of Beast so they stay plain string functions.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

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
// The Origin rule of the live connections: the page's origin is the server's own, or one the
// operator named (allowed_origins, lower case; compared case-insensitively).
bool origin_allowed(std::string_view origin, std::string_view host,
                    const std::vector<std::string>& allowed_origins);

// Well-formed UTF-8 (no overlong forms, surrogates or code points above U+10FFFF): what JSON
// may carry, so that a decoded path or query can be echoed in an answer.
bool is_valid_utf8(std::string_view text);

// Whether a Host header value names this server. DNS rebinding needs a name the attacker
// controls, so every IP literal is accepted, as are loopback names ("localhost",
// "*.localhost") and the given names (case-insensitive, without port); the port is not
// checked (a published Docker port may differ from the one bound).
bool host_is_allowed(std::string_view host, const std::vector<std::string>& allowed_names);

// Whether JSON text nests arrays and objects deeper than limit. A scan of brackets outside
// strings, linear and without recursion; text that is not JSON gives some answer and is left to
// the parser.
bool json_deeper_than(std::string_view text, std::size_t limit);

}  // namespace avk::server
