#pragma once
// The Clearpath frontseat protocol (Kingfisher M200, Heron): NMEA-0183 style sentences over TCP.
// parse_sentence is a pure function over the bytes of one line; whatever arrives, it returns a
// typed sentence or a typed error naming the field, and never throws or reads out of bounds.
// The formatters write what the emulator and the backseat send. Protocol facts: docs/m200.md.
//
// Conventions in every sentence type: times are seconds since midnight UTC (hhmmss.sss on the
// wire); latitude and longitude are signed decimal degrees (+ north, + east; ddmm.mmmm and a
// hemisphere letter on the wire); headings are degrees clockwise from true north in [0, 360);
// angular rates degrees per second; thrust percent of full scale in [-100, 100].

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace avk::vehicle {

// From `$` to the end of the checksum, the line ending not counted, and a missing checksum counted
// as the three bytes it would take. NMEA-0183 allows 82 bytes, but the frontseat's own sentences
// run longer with six decimals.
inline constexpr std::size_t kNmeaMaxLineBytes = 256;

// ---- Frontseat → backseat -------------------------------------------------------------------

// $CPNVG: the frontseat's navigation solution (5 Hz).
struct Cpnvg {
  double time_s = 0.0;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  bool position_ok = false;          // position quality: 1 with GPS, 0 without
  std::optional<double> altitude_m;  // above the bottom; blank on surface vehicles
  std::optional<double> depth_m;     // below the surface; blank on surface vehicles
  double heading_deg = 0.0;
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  double nav_time_s = 0.0;  // when the pose was computed; time_s when the field is blank
  bool operator==(const Cpnvg&) const = default;
};

// $CPNVR: velocities and body rates (5 Hz).
struct Cpnvr {
  double time_s = 0.0;
  double v_east_mps = 0.0;
  double v_north_mps = 0.0;
  double v_down_mps = 0.0;
  double pitch_rate_dps = 0.0;
  double roll_rate_dps = 0.0;
  double yaw_rate_dps = 0.0;
  bool operator==(const Cpnvr&) const = default;
};

// $CPRBS: battery status (0.5 Hz). Some firmware puts a battery id before the voltages.
struct Cprbs {
  double time_s = 0.0;
  std::optional<int> battery_id;
  double stack_v = 0.0;
  double min_v = 0.0;
  double max_v = 0.0;
  double temperature_c = 0.0;
  bool operator==(const Cprbs&) const = default;
};

// $CPRCM: compass. Field order from Clearpath's heron_nmea reference: time, compass id, heading,
// pitch, roll, time of the IMU message.
struct Cprcm {
  double time_s = 0.0;
  int compass_id = 0;
  double heading_deg = 0.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  double imu_time_s = 0.0;
  bool operator==(const Cprcm&) const = default;
};

// $CPIMU: body rates (deg/s) and linear accelerations about x, y, z. The accelerations are kept
// in the unit the frontseat sends: the Heron sends g (z reads about -1 at rest), others may not.
struct Cpimu {
  double time_s = 0.0;
  double rate_x_dps = 0.0;
  double rate_y_dps = 0.0;
  double rate_z_dps = 0.0;
  double accel_x = 0.0;
  double accel_y = 0.0;
  double accel_z = 0.0;
  bool operator==(const Cpimu&) const = default;
};

// $CPALT: time and one reading. Clearpath's heron_nmea reference documents it as the lights
// state (1 on, 0 off), while the name reads as an altimeter; which one a given firmware means is
// unverified, so the value is kept as a number (finite, |value| <= 1e5) and not interpreted.
struct Cpalt {
  double time_s = 0.0;
  double value = 0.0;
  bool operator==(const Cpalt&) const = default;
};

struct NmeaDate {
  int year = 2000;  // two digits on the wire: 80-99 are 19yy (GPS began in 1980), others 20yy
  int month = 1;
  int day = 1;
  bool operator==(const NmeaDate&) const = default;
};

// Speed over ground is in knots on the wire (GPRMC, GPVTG).
inline constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;

// The GPS sentences passed through from the receiver. Any GNSS talker (GP, GN, GL, GA, GB, BD,
// GQ) maps to the same type; the talker is kept. Receivers without a fix blank time, position
// and speed, so those are optional.
struct Gprmc {
  std::string talker = "GP";
  std::optional<double> time_s;
  bool valid = false;  // status A (valid) or V (void)
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;
  std::optional<double> speed_knots;
  std::optional<double> course_deg;
  std::optional<NmeaDate> date;
  std::optional<double> magnetic_variation_deg;  // + east
  std::optional<char> mode;                      // NMEA 2.3 and later: A, D, E, F, M, N, P, R, S
  std::optional<char> nav_status;                // NMEA 4.1 and later: S, C, U, V

  std::optional<double> speed_mps() const;
  bool operator==(const Gprmc&) const = default;
};

struct Gpgga {
  std::string talker = "GP";
  std::optional<double> time_s;
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;
  int quality = 0;  // 0 no fix, 1 GPS, 2 DGPS, ... 8 simulation
  std::optional<int> satellites;
  std::optional<double> hdop;
  std::optional<double> altitude_m;          // above mean sea level
  std::optional<double> geoid_separation_m;  // ellipsoid above geoid
  std::optional<double> dgps_age_s;
  std::optional<int> dgps_station;
  bool operator==(const Gpgga&) const = default;
};

struct Gpvtg {
  std::string talker = "GP";
  std::optional<double> course_true_deg;
  std::optional<double> course_magnetic_deg;
  std::optional<double> speed_knots;
  std::optional<double> speed_kmh;
  std::optional<char> mode;  // NMEA 2.3 and later

  std::optional<double> speed_mps() const;
  bool operator==(const Gpvtg&) const = default;
};

// ---- Backseat → frontseat -------------------------------------------------------------------

struct Pydir {  // direct thrust
  double left_pct = 0.0;
  double right_pct = 0.0;
  bool operator==(const Pydir&) const = default;
};

struct Pydev {  // desired heading and speed, for frontseats with their own controller
  double heading_deg = 0.0;
  double speed_mps = 0.0;  // in [0, 100]
  bool operator==(const Pydev&) const = default;
};

struct Pydep {  // desired yaw rate and thrust
  double yaw_rate_dps = 0.0;
  double thrust_pct = 0.0;
  bool operator==(const Pydep&) const = default;
};

// $PYCLT: lights. Clearpath's table reads 1 as on; the ROS topic behind it is named
// disable_lights, so which sense the firmware takes is unverified.
struct Pyclt {
  bool lights_on = false;
  bool operator==(const Pyclt&) const = default;
};

// A well-formed sentence of a kind not parsed here (GPGSV, GPGSA, CPTIME, ...): real frontseats
// send them, so they are not errors.
struct UnknownSentence {
  std::string address;  // talker and type, e.g. "GPGSV"
  std::vector<std::string> fields;
  bool operator==(const UnknownSentence&) const = default;
};

using NmeaSentence = std::variant<Cpnvg, Cpnvr, Cprbs, Cprcm, Cpimu, Cpalt, Gprmc, Gpgga, Gpvtg,
                                  Pydir, Pydev, Pydep, Pyclt, UnknownSentence>;

// ---- Parsing --------------------------------------------------------------------------------

struct NmeaError {
  enum class Code {
    empty,             // nothing but a line ending
    oversized,         // longer than kNmeaMaxLineBytes
    no_dollar,         // does not start with `$`
    bad_character,     // a byte outside printable ASCII, or a `$` inside the sentence
    missing_checksum,  // no `*hh` where one is required
    bad_checksum,      // not two hex digits, or does not match
    bad_address,       // the sentence id is not 2 to 10 upper-case letters and digits
    bad_field_count,
    missing_field,  // a required field is blank
    non_numeric,
    bad_value,  // a letter or flag field with a value it cannot take, a time not hhmmss
    out_of_range,
  };
  Code code = Code::empty;
  std::string message;    // names the sentence and the field
  std::size_t field = 0;  // 1 is the first after the sentence id; 0 for the line as a whole
  bool operator==(const NmeaError&) const = default;
};
const char* to_string(NmeaError::Code code);

// Who sent the line decides the checksum rule. The frontseat always sends one. Older backseat
// drivers sent `$PYDIR,l,r*` with no digits or no `*` at all, and frontseats accept that.
enum class NmeaDirection { frontseat_to_backseat, backseat_to_frontseat };

enum class NmeaChecksum {
  upper_case,  // as the protocol sends it
  lower_case,  // accepted, but not what a Clearpath frontseat sends: worth counting
  blank,       // `*` and no digits (backseat → frontseat only)
  absent,      // no `*` (backseat → frontseat only)
};

struct NmeaParseResult {
  std::variant<NmeaSentence, NmeaError> value;
  NmeaChecksum checksum = NmeaChecksum::absent;  // how the line carried it, when it parsed

  bool ok() const { return value.index() == 0; }
  const NmeaSentence* sentence() const { return std::get_if<NmeaSentence>(&value); }
  const NmeaError* error() const { return std::get_if<NmeaError>(&value); }
};

// One line, with or without its trailing CR/LF. Direction says whose checksum rule applies; any
// sentence type parses in either direction.
NmeaParseResult parse_sentence(std::string_view line, NmeaDirection direction);

// XOR of the bytes of body: pass what lies between `$` and `*`.
std::uint8_t nmea_checksum(std::string_view body);

// ---- Formatting -----------------------------------------------------------------------------
// `$...*HH\r\n`, upper-case checksum; numbers with up to 6 decimals, trailing zeros stripped
// (headings that round to 360 are written 0). CPNVG longitudes are not zero-padded, as the
// frontseat writes them; GPS sentences zero-pad, as receivers do. parse_sentence reads every
// formatted sentence back equal within that precision. A value the parser would reject
// (non-finite, out of range) throws std::invalid_argument naming the field, so a bad value shows
// at the sender rather than as a parse error at the other end.

std::string format_sentence(const NmeaSentence& sentence);
std::string format_pydir(double left_pct, double right_pct);
std::string format_cpnvg(const Cpnvg& s);
std::string format_cpnvr(const Cpnvr& s);
std::string format_cprbs(const Cprbs& s);
std::string format_gprmc(const Gprmc& s);

}  // namespace avk::vehicle
