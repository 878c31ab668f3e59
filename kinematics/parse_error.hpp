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
        position_(position),
        message_(what) {}
  const std::string& field() const { return field_; }
  std::size_t position() const { return position_; }
  // The message without the field and position, for reports that list the field on its own.
  const std::string& message() const { return message_; }

 private:
  std::string field_;
  std::size_t position_;
  std::string message_;
};

}  // namespace avk::kinematics
