#pragma once
// One JSON reader for every document the project takes from outside (turns, CKT files, mission
// and sim configs). nlohmann's own parse throws its exceptions (out_of_range.406 for 1e400, whose
// text quotes the input), keeps the last of duplicate keys silently and builds a tree of any depth
// that later recursive code (dump, compare, destroy) may overflow the stack on. This reader bounds
// depth, width and size while building, rejects duplicate keys, and throws only ParseError with
// messages of its own.

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "kinematics/parse_error.hpp"

namespace avk::kinematics {

struct JsonLimits {
  std::size_t max_depth = 32;  // nested arrays and objects; no project document needs 10
  std::size_t max_values = std::size_t{1} << 22;
  std::size_t max_array_elements = std::size_t{1} << 22;
  std::size_t max_object_keys = 1024;
};

// A document the lexer stopped on: field() is "json" and position() the 0-based byte offset of the
// offending byte (or the text size at an early end). pointer() is the JSON pointer of the value
// being read ("/" for the document itself), so a number out of range can be reported against
// its field.
class JsonSyntaxError : public ParseError {
 public:
  JsonSyntaxError(std::size_t offset, std::string pointer, std::string reason, std::size_t line,
                  std::size_t column);
  const std::string& pointer() const { return pointer_; }
  const std::string& reason() const { return reason_; }  // without position
  std::size_t line() const { return line_; }             // 1-based
  std::size_t column() const { return column_; }         // 1-based
  bool number_out_of_range() const { return out_of_range_; }

 private:
  std::string pointer_;
  std::string reason_;
  std::size_t line_;
  std::size_t column_;
  bool out_of_range_;
};

// Throws JsonSyntaxError for malformed JSON, ParseError(JSON pointer, 0, message) for a document
// past the limits or with a duplicate key.
nlohmann::json parse_json_bounded(std::string_view text, const JsonLimits& limits = {});

// What a nlohmann parse error is about, in words of this project's own: nlohmann's message quotes
// the last token read, which may be megabytes of the caller's input.
std::string json_error_reason(const nlohmann::json::exception& ex);

// The JSON pointer token of an object key ('~' and '/' escaped), with its leading '/'.
std::string json_member_pointer(std::string_view key);

}  // namespace avk::kinematics
