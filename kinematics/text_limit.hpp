#pragma once
// Free text that comes from outside (a mission's name, a vehicle id, an imported file's messages)
// is bounded before it is stored: names are listed and shown everywhere, and one of 900 kB makes
// every list of missions 900 kB. Every reader words the refusal the same way.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace avk::kinematics {

// "must be at most 256 bytes (UTF-8), got 900000" when the text is longer; none when it fits.
inline std::optional<std::string> text_too_long(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return std::nullopt;
  return "must be at most " + std::to_string(max_bytes) + " bytes (UTF-8), got " +
         std::to_string(text.size());
}

}  // namespace avk::kinematics
