#pragma once
// The JSON form of a TurnSequence, for files and the station's HTTP API. Format:
// docs/turn-record-format.md. Doubles are written shortest-round-trip, so
// turn_from_json(to_json(t)) == t and parse_turn_json(to_json_string(t)) == t exactly.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::kinematics {

// Throws std::invalid_argument for a turn JSON cannot hold: NaN/infinity (JSON has no spelling for
// them and writing null would lose the value silently), strings that are not UTF-8, or more
// samples/warnings than the limits in turn_text.hpp.
nlohmann::json to_json(const TurnSequence& turn);

// Throws ParseError(field = JSON pointer of the offending value such as "/samples/3/2",
// position = the sample index for errors inside /samples, else 0, message).
TurnSequence turn_from_json(const nlohmann::json& j);

// Compact, no newline. Same exceptions as to_json, and std::invalid_argument past the byte limit.
std::string to_json_string(const TurnSequence& turn);

// Syntax errors (and numbers out of the range of a double) throw ParseError("json", 0-based byte
// offset where the lexer stopped: the offending byte, or the text size at an early end, message).
// Duplicate keys, nesting deeper than a turn has and oversized arrays throw with a JSON pointer and
// sample index like turn_from_json, which then checks the document.
TurnSequence parse_turn_json(std::string_view text);

}  // namespace avk::kinematics
