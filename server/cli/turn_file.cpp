#include "server/cli/turn_file.hpp"

#include <stdexcept>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_json.hpp"
#include "kinematics/turn_text.hpp"

namespace avk::server {

std::vector<TurnRecordLine> parse_turn_file(std::string_view content, const std::string& name) {
  std::vector<TurnRecordLine> out;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos < content.size()) {
    std::size_t end = content.find('\n', pos);
    if (end == std::string_view::npos) end = content.size();
    std::string_view line = content.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    try {
      if (line[first] == '{') {
        out.push_back({kinematics::parse_turn_json(line), TurnFormat::json});
      } else {
        out.push_back({kinematics::parse_text_record(line), TurnFormat::text});
      }
    } catch (const kinematics::ParseError& e) {
      throw std::runtime_error(name + ":" + std::to_string(line_no) + ": " + e.what());
    }
  }
  return out;
}

std::string format_turn(const kinematics::TurnSequence& turn, TurnFormat format) {
  return format == TurnFormat::json ? kinematics::to_json_string(turn)
                                    : kinematics::to_text_record(turn);
}

}  // namespace avk::server
