#pragma once
// The small text rules every NMEA reader and writer shares: digits, hex, the decimal numbers the
// protocol writes, the GNSS talkers, and how a bad field is quoted in a message.

#include <optional>
#include <string>
#include <string_view>

namespace avk::vehicle::nmea {

bool is_digit(char c);
bool all_digits(std::string_view s);
// The value of one hex digit, -1 for any other character.
int hex_value(char c);

// A field for an error message, cut short: a garbage field must not flood a message with 200
// bytes.
std::string quoted(std::string_view s);

// The shortest text that reads back as the same double ("?" if it cannot be written).
std::string number_text(double v);

// Decimal numbers as the protocol writes them: an optional sign, digits, an optional fraction.
// No exponent, no inf or nan: from_chars alone would take those.
std::optional<double> decimal(std::string_view s);

// GP, GN, GL, GA, GB, BD, GQ, GI: the talkers whose RMC, GGA and VTG map to the typed sentences.
bool is_gnss_talker(std::string_view talker);

}  // namespace avk::vehicle::nmea
