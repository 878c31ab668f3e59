#pragma once
// AIVDM sentences of the simulated traffic, as an AIS transponder's receiver would put them out:
// the message's bits (ITU-R M.1371) armoured six bits to a character, fill bits to a whole
// character, split into sentences of at most 60 payload characters (a type 5 takes two, which
// share a sequence id), each framed `!AIVDM,count,number,sequence,channel,payload,fill*hh\r\n`
// (IEC 61162-1). No Debian C/C++ library encodes AIS, so the few message types the simulator sends
// are written here; gpsd decodes them in the tests.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace avk::sim {

struct AisPositionMessage {
  std::uint32_t mmsi = 0;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  bool accuracy_high = false;
  std::optional<double> speed_mps;
  std::optional<double> course_deg;
  std::optional<double> heading_deg;
  int nav_status = 15;  // types 1-3 only; 15 is "not defined"
  int utc_second = 60;  // 60 is "not available"
};

struct AisStaticMessage {
  std::uint32_t mmsi = 0;
  std::string name;      // upper-cased; at most 20 characters are sent
  std::string callsign;  // at most 7
  int ship_type = 0;     // 0 is "not available"
  std::string destination;
};

// Type 1 (a Class A position report) and type 18 (Class B): one sentence each.
std::vector<std::string> encode_class_a_position(const AisPositionMessage& m, char channel = 'A');
std::vector<std::string> encode_class_b_position(const AisPositionMessage& m, char channel = 'B');
// Type 5 (Class A static and voyage data): two sentences with sequence id sequence_id (0-9).
std::vector<std::string> encode_static_voyage(const AisStaticMessage& m, int sequence_id,
                                              char channel = 'A');

// Sentences of a message's bits ('0'/'1' characters, any length): exposed for the tests.
std::vector<std::string> aivdm_sentences(const std::string& bits, int sequence_id, char channel);

}  // namespace avk::sim
