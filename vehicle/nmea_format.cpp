#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <variant>

#include "vehicle/nmea.hpp"
#include "vehicle/nmea_text.hpp"

namespace avk::vehicle {

namespace {

using nmea::is_gnss_talker;
using nmea::number_text;
using nmea::quoted;

// Builds `$ADDRESS,f1,...*HH\r\n`. Values it cannot represent faithfully are written so that the
// check in format_checked rejects them with the field's name: non-finite as nan/inf, magnitudes
// beyond every range in exponent form (never valid on the wire).
class Writer {
 public:
  explicit Writer(std::string_view address) {
    out_.reserve(128);
    out_ += '$';
    out_ += address;
  }

  Writer& blank() {
    out_ += ',';
    return *this;
  }

  Writer& text(std::string_view s) {
    out_ += ',';
    out_ += s;
    return *this;
  }

  Writer& letter(char c) {
    out_ += ',';
    out_ += c;
    return *this;
  }

  Writer& integer(long long v) { return text(std::to_string(v)); }

  Writer& number(double v) {
    out_ += ',';
    append_number(v);
    return *this;
  }

  Writer& number(const std::optional<double>& v) { return v ? number(*v) : blank(); }

  Writer& heading(double v) {
    out_ += ',';
    const std::size_t at = out_.size();
    append_number(v);
    if (std::string_view(out_).substr(at) == "360") out_.replace(at, 3, "0");
    return *this;
  }

  Writer& heading(const std::optional<double>& v) { return v ? heading(*v) : blank(); }

  // hhmmss with up to six decimals of seconds. Times past midnight wrap: an emulator may count
  // seconds since it started.
  Writer& time(double t_s, const char* what) {
    if (!std::isfinite(t_s) || t_s < 0.0 || t_s > 1e12)
      throw std::invalid_argument(std::string(what) + " " + number_text(t_s) +
                                  " is not a time of day in seconds");
    constexpr long long kDay_us = 86400LL * 1000000LL;
    const long long us = std::llround(t_s * 1e6) % kDay_us;
    const long long s = us / 1000000;
    char buf[32];
    std::snprintf(buf, sizeof buf, ",%02lld%02lld%02lld", s / 3600, s / 60 % 60, s % 60);
    out_ += buf;
    append_fraction(us % 1000000);
    return *this;
  }

  Writer& time(const std::optional<double>& t_s, const char* what) {
    return t_s ? time(*t_s, what) : blank();
  }

  // ddmm.mmmmmm,N or dddmm.mmmmmm,E: the minutes rounded to six decimals in integers, so that
  // 59.9999999' carries into the degrees instead of being written 60.
  Writer& coordinate(double deg, bool latitude, bool pad) {
    const double limit = latitude ? 90.0 : 180.0;
    if (!std::isfinite(deg) || std::abs(deg) > limit)
      throw std::invalid_argument(std::string(latitude ? "latitude " : "longitude ") +
                                  number_text(deg) + " is out of range [-" + number_text(limit) +
                                  ", " + number_text(limit) + "]");
    const long long micro_minutes = std::llround(std::abs(deg) * 60e6);
    const long long degrees = micro_minutes / 60000000;
    const long long rest = micro_minutes % 60000000;
    char buf[32];
    if (latitude) {
      std::snprintf(buf, sizeof buf, ",%02lld%02lld", degrees, rest / 1000000);
    } else {
      std::snprintf(buf, sizeof buf, pad ? ",%03lld%02lld" : ",%lld%02lld", degrees,
                    rest / 1000000);
    }
    out_ += buf;
    append_fraction(rest % 1000000);
    const bool negative = deg < 0.0 && micro_minutes != 0;
    return letter(latitude ? (negative ? 'S' : 'N') : (negative ? 'W' : 'E'));
  }

  Writer& position(const std::optional<double>& lat, const std::optional<double>& lon, bool pad) {
    if (lat.has_value() != lon.has_value())
      throw std::invalid_argument("latitude and longitude must be both given or both blank");
    if (!lat) return blank().blank().blank().blank();
    return coordinate(*lat, true, pad).coordinate(*lon, false, pad);
  }

  std::string finish() {
    const std::uint8_t sum = nmea_checksum(std::string_view(out_).substr(1));
    char buf[8];
    std::snprintf(buf, sizeof buf, "*%02X\r\n", static_cast<unsigned>(sum));
    out_ += buf;
    return std::move(out_);
  }

 private:
  void append_number(double v) {
    char buf[64];
    const auto fmt = std::isfinite(v) && std::abs(v) < 1e9 ? std::chars_format::fixed
                                                           : std::chars_format::scientific;
    auto r = std::to_chars(buf, buf + sizeof buf, v, fmt, 6);
    std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
    if (fmt == std::chars_format::fixed && s.find('.') != std::string_view::npos) {
      while (s.back() == '0')
        s.remove_suffix(1);
      if (s.back() == '.') s.remove_suffix(1);
    }
    if (s == "-0") s = "0";
    out_ += s;
  }

  // A fraction in millionths as .dddddd, trailing zeros stripped, nothing for zero.
  void append_fraction(long long millionths) {
    if (millionths == 0) return;
    char buf[16];
    std::snprintf(buf, sizeof buf, ".%06lld", millionths);
    std::string_view s(buf);
    while (s.back() == '0')
      s.remove_suffix(1);
    out_ += s;
  }

  std::string out_;
};

std::string date_text(const NmeaDate& d) {
  if (d.year < 1980 || d.year > 2079)
    throw std::invalid_argument("date year " + std::to_string(d.year) +
                                " is outside 1980-2079, which ddmmyy can hold");
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d%02d%02d", std::clamp(d.day, 0, 99),
                std::clamp(d.month, 0, 99), d.year % 100);
  return buf;
}

std::string talker_of(const std::string& talker) {
  if (!is_gnss_talker(talker))
    throw std::invalid_argument("talker " + quoted(talker) + " is not a GNSS talker");
  return talker;
}

std::string write(const Cpnvg& s) {
  Writer w("CPNVG");
  w.time(s.time_s, "time").coordinate(s.lat_deg, true, false).coordinate(s.lon_deg, false, false);
  w.letter(s.position_ok ? '1' : '0').number(s.altitude_m).number(s.depth_m);
  w.heading(s.heading_deg).number(s.roll_deg).number(s.pitch_deg).time(s.nav_time_s, "nav time");
  return w.finish();
}

std::string write(const Cpnvr& s) {
  Writer w("CPNVR");
  w.time(s.time_s, "time").number(s.v_east_mps).number(s.v_north_mps).number(s.v_down_mps);
  w.number(s.pitch_rate_dps).number(s.roll_rate_dps).number(s.yaw_rate_dps);
  return w.finish();
}

std::string write(const Cprbs& s) {
  Writer w("CPRBS");
  w.time(s.time_s, "time");
  if (s.battery_id) w.integer(*s.battery_id);
  w.number(s.stack_v).number(s.min_v).number(s.max_v).number(s.temperature_c);
  return w.finish();
}

std::string write(const Cprcm& s) {
  Writer w("CPRCM");
  w.time(s.time_s, "time").integer(s.compass_id).heading(s.heading_deg);
  w.number(s.pitch_deg).number(s.roll_deg).time(s.imu_time_s, "imu time");
  return w.finish();
}

std::string write(const Cpimu& s) {
  Writer w("CPIMU");
  w.time(s.time_s, "time").number(s.rate_x_dps).number(s.rate_y_dps).number(s.rate_z_dps);
  w.number(s.accel_x).number(s.accel_y).number(s.accel_z);
  return w.finish();
}

std::string write(const Cpalt& s) {
  Writer w("CPALT");
  w.time(s.time_s, "time").number(s.value);
  return w.finish();
}

std::string write(const Gprmc& s) {
  Writer w(talker_of(s.talker) + "RMC");
  w.time(s.time_s, "time").letter(s.valid ? 'A' : 'V').position(s.lat_deg, s.lon_deg, true);
  w.number(s.speed_knots).heading(s.course_deg);
  if (s.date) {
    w.text(date_text(*s.date));
  } else {
    w.blank();
  }
  if (s.magnetic_variation_deg) {
    w.number(std::abs(*s.magnetic_variation_deg))
        .letter(*s.magnetic_variation_deg < 0.0 ? 'W' : 'E');
  } else {
    w.blank().blank();
  }
  // The mode is written when either later field is: the status cannot come without it.
  if (s.mode || s.nav_status) {
    if (s.mode) {
      w.letter(*s.mode);
    } else {
      w.blank();
    }
  }
  if (s.nav_status) w.letter(*s.nav_status);
  return w.finish();
}

std::string write(const Gpgga& s) {
  Writer w(talker_of(s.talker) + "GGA");
  w.time(s.time_s, "time").position(s.lat_deg, s.lon_deg, true).integer(s.quality);
  if (s.satellites) {
    w.integer(*s.satellites);
  } else {
    w.blank();
  }
  w.number(s.hdop).number(s.altitude_m).letter('M').number(s.geoid_separation_m).letter('M');
  w.number(s.dgps_age_s);
  if (s.dgps_station) {
    w.integer(*s.dgps_station);
  } else {
    w.blank();
  }
  return w.finish();
}

std::string write(const Gpvtg& s) {
  Writer w(talker_of(s.talker) + "VTG");
  w.heading(s.course_true_deg).letter('T').heading(s.course_magnetic_deg).letter('M');
  w.number(s.speed_knots).letter('N').number(s.speed_kmh).letter('K');
  if (s.mode) w.letter(*s.mode);
  return w.finish();
}

std::string write(const Pydir& s) {
  Writer w("PYDIR");
  w.number(s.left_pct).number(s.right_pct);
  return w.finish();
}

std::string write(const Pydev& s) {
  Writer w("PYDEV");
  w.heading(s.heading_deg).number(s.speed_mps);
  return w.finish();
}

std::string write(const Pydep& s) {
  Writer w("PYDEP");
  w.number(s.yaw_rate_dps).number(s.thrust_pct);
  return w.finish();
}

std::string write(const Pyclt& s) {
  Writer w("PYCLT");
  w.letter(s.lights_on ? '1' : '0');
  return w.finish();
}

std::string write(const UnknownSentence& s) {
  Writer w(s.address);
  for (const std::string& f : s.fields) {
    if (f.find_first_of(",*") != std::string::npos)
      throw std::invalid_argument("field " + quoted(f) + " holds a ',' or '*'");
    w.text(f);
  }
  return w.finish();
}

// Writes a sentence and reads it back: the parser is the one statement of the protocol's
// ranges, so what it would reject never leaves the sender.
template <class T>
std::string format_checked(const T& s, const char* what) {
  std::string line;
  try {
    line = write(s);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(what) + ": " + e.what());
  }
  const NmeaParseResult back = parse_sentence(line, NmeaDirection::frontseat_to_backseat);
  if (const NmeaError* e = back.error())
    throw std::invalid_argument(std::string(what) + ": " + e->message);
  if (!std::holds_alternative<T>(*back.sentence()))
    throw std::invalid_argument(std::string(what) + ": " + quoted(line) +
                                " reads back as another sentence type");
  return line;
}

}  // namespace

std::string format_sentence(const NmeaSentence& sentence) {
  return std::visit([](const auto& s) { return format_checked(s, "format_sentence"); }, sentence);
}

std::string format_pydir(double left_pct, double right_pct) {
  return format_checked(Pydir{left_pct, right_pct}, "format_pydir");
}

std::string format_cpnvg(const Cpnvg& s) {
  return format_checked(s, "format_cpnvg");
}

std::string format_cpnvr(const Cpnvr& s) {
  return format_checked(s, "format_cpnvr");
}

std::string format_cprbs(const Cprbs& s) {
  return format_checked(s, "format_cprbs");
}

std::string format_gprmc(const Gprmc& s) {
  return format_checked(s, "format_gprmc");
}

}  // namespace avk::vehicle
