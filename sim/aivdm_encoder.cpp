#include "sim/aivdm_encoder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "vehicle/ais_fields.hpp"
#include "vehicle/nmea.hpp"

namespace avk::sim {

namespace {

// At most 60 payload characters per sentence keeps a sentence within NMEA's 82 bytes.
constexpr std::size_t kMaxPayloadChars = 60;

class Bits {
 public:
  void put(std::uint64_t value, int width) {
    for (int i = width - 1; i >= 0; --i)
      bits_ += ((value >> i) & 1u) ? '1' : '0';
  }
  void put_signed(std::int64_t value, int width) {
    put(static_cast<std::uint64_t>(value) & ((std::uint64_t{1} << width) - 1), width);
  }
  // Six-bit ASCII: '@' to '_' are 0 to 31, ' ' to '?' are 32 to 63; padded with '@'.
  void put_text(const std::string& text, std::size_t chars) {
    for (std::size_t i = 0; i < chars; ++i) {
      char c = i < text.size()
                   ? static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])))
                   : '@';
      if (c < ' ' || c > '_') c = '?';
      put(c >= '@' ? c - '@' : c, 6);
    }
  }
  const std::string& str() const { return bits_; }

 private:
  std::string bits_;
};

std::uint32_t checked_mmsi(std::uint32_t mmsi) {
  if (mmsi == 0 || mmsi > 999999999u) throw std::invalid_argument("mmsi: not a 9-digit MMSI");
  return mmsi;
}

std::int64_t lat_lon_units(double deg, double limit, const char* field) {
  if (!std::isfinite(deg) || std::abs(deg) > limit)
    throw std::invalid_argument(std::string(field) + ": out of range");
  return std::llround(deg * vehicle::kAisLatLonPerDeg);
}

unsigned speed_units(const std::optional<double>& speed_mps) {
  if (!speed_mps) return vehicle::kAisSpeedNotAvailable;
  if (!std::isfinite(*speed_mps) || *speed_mps < 0.0)
    throw std::invalid_argument("speed_mps: not a speed");
  const double deciknots = *speed_mps / vehicle::kMetresPerSecondPerKnot * 10.0;
  return static_cast<unsigned>(std::min<double>(std::llround(deciknots), vehicle::kAisSpeedMax));
}

double wrapped_deg(double deg, const char* field) {
  if (!std::isfinite(deg)) throw std::invalid_argument(std::string(field) + ": not finite");
  const double w = std::fmod(deg, 360.0);
  return w < 0.0 ? w + 360.0 : w;
}

unsigned course_units(const std::optional<double>& course_deg) {
  if (!course_deg) return vehicle::kAisCourseNotAvailable;
  return static_cast<unsigned>(std::llround(wrapped_deg(*course_deg, "course_deg") * 10.0)) % 3600;
}

unsigned heading_units(const std::optional<double>& heading_deg) {
  if (!heading_deg) return vehicle::kAisHeadingNotAvailable;
  return static_cast<unsigned>(std::llround(wrapped_deg(*heading_deg, "heading_deg"))) % 360;
}

// The fields types 1 and 18 share, from speed over ground to the heading.
void put_motion(Bits& b, const AisPositionMessage& m) {
  b.put(speed_units(m.speed_mps), 10);
  b.put(m.accuracy_high ? 1 : 0, 1);
  b.put_signed(lat_lon_units(m.lon_deg, 180.0, "lon_deg"), 28);
  b.put_signed(lat_lon_units(m.lat_deg, 90.0, "lat_deg"), 27);
  b.put(course_units(m.course_deg), 12);
  b.put(heading_units(m.heading_deg), 9);
  b.put(static_cast<unsigned>(std::clamp(m.utc_second, 0, 63)), 6);
}

char armoured(unsigned six_bits) {
  return static_cast<char>(six_bits < 40 ? six_bits + 48 : six_bits + 56);
}

}  // namespace

std::vector<std::string> aivdm_sentences(const std::string& bits, int sequence_id, char channel) {
  const std::size_t fill = (6 - bits.size() % 6) % 6;
  std::string padded = bits + std::string(fill, '0');
  std::string payload;
  for (std::size_t i = 0; i < padded.size(); i += 6)
    payload += armoured(static_cast<unsigned>(std::stoul(padded.substr(i, 6), nullptr, 2)));
  const std::size_t count =
      std::max<std::size_t>(1, (payload.size() + kMaxPayloadChars - 1) / kMaxPayloadChars);
  if (count > 9) throw std::invalid_argument("bits: more than 9 sentences");
  std::vector<std::string> out;
  for (std::size_t n = 0; n < count; ++n) {
    const bool last = n + 1 == count;
    std::string body = "AIVDM,";
    body += std::to_string(count);
    body += ',';
    body += std::to_string(n + 1);
    body += ',';
    if (count > 1) body += std::to_string(sequence_id % 10);
    body += ",";
    body += channel;
    body += ',';
    body += std::string_view(payload).substr(n * kMaxPayloadChars, kMaxPayloadChars);
    body += ',';
    body += std::to_string(last ? fill : 0);
    char sum[8];
    std::snprintf(sum, sizeof sum, "*%02X\r\n",
                  static_cast<unsigned>(vehicle::nmea_checksum(body)));
    std::string line(1, '!');
    line += body;
    line += sum;
    out.push_back(std::move(line));
  }
  return out;
}

std::vector<std::string> encode_class_a_position(const AisPositionMessage& m, char channel) {
  Bits b;
  b.put(1, 6);  // message type
  b.put(0, 2);  // repeat indicator
  b.put(checked_mmsi(m.mmsi), 30);
  b.put(static_cast<unsigned>(std::clamp(m.nav_status, 0, 15)), 4);
  b.put_signed(-128, 8);  // rate of turn: not available
  put_motion(b, m);
  b.put(0, 2);   // manoeuvre indicator: not available
  b.put(0, 3);   // spare
  b.put(0, 1);   // RAIM
  b.put(0, 19);  // radio status
  return aivdm_sentences(b.str(), 0, channel);
}

std::vector<std::string> encode_class_b_position(const AisPositionMessage& m, char channel) {
  Bits b;
  b.put(18, 6);
  b.put(0, 2);
  b.put(checked_mmsi(m.mmsi), 30);
  b.put(0, 8);  // reserved
  put_motion(b, m);
  b.put(0, 2);   // regional reserved
  b.put(1, 1);   // a carrier-sense (CS) unit
  b.put(0, 4);   // display, DSC, band, message 22 flags
  b.put(0, 1);   // assigned mode
  b.put(0, 1);   // RAIM
  b.put(0, 20);  // radio status
  return aivdm_sentences(b.str(), 0, channel);
}

std::vector<std::string> encode_static_voyage(const AisStaticMessage& m, int sequence_id,
                                              char channel) {
  Bits b;
  b.put(5, 6);
  b.put(0, 2);
  b.put(checked_mmsi(m.mmsi), 30);
  b.put(0, 2);   // AIS version
  b.put(0, 30);  // IMO number: not available
  b.put_text(m.callsign, 7);
  b.put_text(m.name, 20);
  b.put(static_cast<unsigned>(std::clamp(m.ship_type, 0, 99)), 8);
  b.put(0, 9 + 9 + 6 + 6);  // dimensions: not available
  b.put(1, 4);              // position fix device: GPS
  b.put(0, 4 + 5);          // ETA month and day: not available
  b.put(24, 5);             // ETA hour: not available
  b.put(60, 6);             // ETA minute: not available
  b.put(0, 8);              // draught: not available
  b.put_text(m.destination, 20);
  b.put(0, 1);  // DTE: ready
  b.put(0, 1);  // spare
  return aivdm_sentences(b.str(), sequence_id, channel);
}

}  // namespace avk::sim
