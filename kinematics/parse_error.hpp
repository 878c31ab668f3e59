#pragma once
// The error every parser in the project throws for malformed input: it names the field and the
// position (byte offset for text, line for line-based files, JSON pointer path for JSON).

#include <cstddef>
#include <stdexcept>
#include <string>

namespace avk::kinematics {

class ParseError : public std::runtime_error {
 public:
  ParseError(std::string field, std::size_t position, const std::string& what)
      : std::runtime_error(what + " (field '" + field + "' at position " +
                           std::to_string(position) + ")"),
        field_(std::move(field)),
        position_(position) {}
  const std::string& field() const { return field_; }
  std::size_t position() const { return position_; }

 private:
  std::string field_;
  std::size_t position_;
};

}  // namespace avk::kinematics
