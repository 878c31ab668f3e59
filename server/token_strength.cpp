#include "server/token_strength.hpp"

#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <vector>

namespace avk::server {

namespace {

// The frequency (plug-in) entropy of a sequence times its length: what the symbols' own
// frequencies say n of them carry.
template <class T>
double frequency_bits(const std::vector<T>& symbols) {
  std::map<T, std::size_t> counts;
  for (const T& s : symbols)
    ++counts[s];
  const double n = static_cast<double>(symbols.size());
  double bits = 0.0;
  for (const auto& [s, k] : counts)
    bits -= static_cast<double>(k) * std::log2(static_cast<double>(k) / n);
  return bits;
}

// The shortest prefix the token repeats (whole or cut short at the end): "abcabca" -> "abc".
std::string_view repeating_unit(std::string_view t) {
  for (std::size_t p = 1; p < t.size(); ++p) {
    bool repeats = true;
    for (std::size_t i = p; i < t.size() && repeats; ++i)
      repeats = t[i] == t[i - p];
    if (repeats) return t.substr(0, p);
  }
  return t;
}

bool header_safe(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 ||
         std::string_view("-._~+/=").find(c) != std::string_view::npos;
}

}  // namespace

double token_entropy_bits(std::string_view token) {
  const std::string_view unit = repeating_unit(token);
  const std::vector<char> chars(unit.begin(), unit.end());
  std::vector<int> steps;
  for (std::size_t i = 1; i < unit.size(); ++i)
    steps.push_back(static_cast<unsigned char>(unit[i]) - static_cast<unsigned char>(unit[i - 1]));
  return std::min(frequency_bits(chars), frequency_bits(steps));
}

std::optional<std::string> token_weakness(std::string_view token) {
  if (token.size() < kMinTokenChars)
    return "must be at least " + std::to_string(kMinTokenChars) + " characters (it has " +
           std::to_string(token.size()) + "); leave it out to have one generated";
  for (const char c : token)
    if (!header_safe(c)) return std::string("may hold only letters, digits and - . _ ~ + / =");
  const std::set<char> distinct(token.begin(), token.end());
  if (distinct.size() < kMinTokenDistinctChars)
    return "has only " + std::to_string(distinct.size()) + " different characters (at least " +
           std::to_string(kMinTokenDistinctChars) +
           " needed): use more varied characters, or leave it out";
  const double bits = token_entropy_bits(token);
  if (bits < kMinTokenBits)
    return "is too predictable (about " + std::to_string(static_cast<int>(bits)) +
           " bits; at least " + std::to_string(static_cast<int>(kMinTokenBits)) +
           " needed, a repeated part counted once and a run of steps as the steps): use a "
           "random token, or leave it out";
  return std::nullopt;
}

}  // namespace avk::server
