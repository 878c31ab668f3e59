#pragma once
// The compact one-line text record of a TurnSequence, the form published as TURN_RECORD_RAW and
// TURN_RECORD (thesis §4.5). Format: docs/turn-record-format.md.
//
//   AVKTURN/1 vehicle_id=m200%20a;mission_id=...;status=ok;...;n_samples=2;samples=0,1,2,3,4|...
//
// Doubles are written shortest-round-trip, so parse_text_record(to_text_record(t)) == t exactly.

#include <cstddef>
#include <string>
#include <string_view>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_sequence.hpp"

namespace avk::kinematics {

// Limits shared by the text and JSON forms. They keep hostile input from making a parser allocate
// without bound; the serialisers refuse turns beyond them so every record written can be read.
inline constexpr std::size_t kMaxTurnRecordSamples = 1'000'000;
inline constexpr std::size_t kMaxTurnRecordWarnings = 10'000;
inline constexpr std::size_t kMaxTurnRecordBytes = std::size_t{64} << 20;

// One line, no newline. Throws std::invalid_argument for a turn no record can hold: a NaN or
// infinite value, a string that is not valid UTF-8, or more samples/warnings/bytes than the limits.
std::string to_text_record(const TurnSequence& turn);

// Throws ParseError(field, byte offset in line, message) for anything but a well-formed record.
TurnSequence parse_text_record(std::string_view line);

// The serialisability checks both formats share: throws std::invalid_argument naming the field.
void check_turn_serialisable(const TurnSequence& turn);

// Strict RFC 3629 UTF-8 (no overlongs, surrogates or code points past U+10FFFF), the same rule the
// JSON parser applies, so a turn accepted by one format can always be written in the other.
bool is_valid_utf8(std::string_view s);

}  // namespace avk::kinematics
