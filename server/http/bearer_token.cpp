#include "server/http/bearer_token.hpp"

#include <cctype>
#include <string_view>

namespace avk::server {

bool bearer_token_matches(const std::string& authorization, const std::string& token) {
  constexpr std::string_view scheme = "bearer";
  if (token.empty() || authorization.size() <= scheme.size()) return false;
  for (std::size_t i = 0; i < scheme.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(authorization[i])) != scheme[i]) return false;
  std::size_t start = scheme.size();
  if (authorization[start] != ' ') return false;
  while (start < authorization.size() && authorization[start] == ' ')
    ++start;
  const std::string_view given = std::string_view(authorization).substr(start);
  unsigned char diff = given.size() == token.size() ? 0 : 1;
  for (std::size_t i = 0; i < token.size(); ++i)
    diff |= static_cast<unsigned char>(token[i] ^ (i < given.size() ? given[i] : 0));
  return diff == 0;
}

}  // namespace avk::server
