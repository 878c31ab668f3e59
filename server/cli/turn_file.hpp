#pragma once
// Files of turn records: one record a line, either the text record or a JSON object (JSON Lines).
// Blank lines and lines starting with '#' are skipped.

#include <string>
#include <string_view>
#include <vector>

#include "kinematics/turn_sequence.hpp"

namespace avk::server {

enum class TurnFormat { text, json };

struct TurnRecordLine {
  kinematics::TurnSequence turn;
  TurnFormat format;
};

// All or nothing: throws std::runtime_error "NAME:LINE: ..." at the first bad record.
std::vector<TurnRecordLine> parse_turn_file(std::string_view content, const std::string& name);

std::string format_turn(const kinematics::TurnSequence& turn, TurnFormat format);

}  // namespace avk::server
