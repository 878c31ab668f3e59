#pragma once
// The station's bearer token check (RFC 6750): the scheme case-insensitive (RFC 7235), one or
// more spaces after it, the token compared in time independent of where it differs.

#include <string>

namespace avk::server {

bool bearer_token_matches(const std::string& authorization, const std::string& token);

}  // namespace avk::server
