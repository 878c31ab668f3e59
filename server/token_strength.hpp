#pragma once
// How hard a bearer token an operator chose (`avk serve --token`) is to guess. It must be as hard
// as the one the station would generate (128 random bits, 32 hex digits): at least 32 characters
// of a header-safe alphabet, at least 10 different ones, and an estimated entropy of at least 96
// bits. The estimate is the smaller of two, each taken over the token's shortest repeating unit
// (a token that is one part said twice counts that part once):
// - the characters' own frequencies times their count, which refuses short alphabets and
//   repeats ("aaaa...", "abab...");
// - the same over the steps from each character to the next, which refuses runs that ascend or
//   descend ("0123456789abcdef...", "fedcba...", "02468...") however many characters they use.
// A random token scores about 117 (hex) or more; about 1 in 5000 random hex tokens is refused,
// and another one drawn passes.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace avk::server {

inline constexpr std::size_t kMinTokenChars = 32;
inline constexpr std::size_t kMinTokenDistinctChars = 10;
inline constexpr double kMinTokenBits = 96.0;

// The estimate above, in bits.
double token_entropy_bits(std::string_view token);

// What is wrong with the token (a sentence fragment: "must be at least 32 characters ..."), or
// nothing when it is strong enough.
std::optional<std::string> token_weakness(std::string_view token);

}  // namespace avk::server
