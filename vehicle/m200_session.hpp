#pragma once
// The backseat side of the Clearpath frontseat protocol for a Kingfisher M200, without any I/O:
// lines from the frontseat in, navigation samples and battery state out; at each controller tick
// the $PYDIR to send, from the backseat PID (pMarinePID) and the differential mixing, or all stop
// when the helm's commands or the navigation have gone stale. The transport (vehicle/m200.hpp)
// feeds it bytes and sends what it returns, so everything here is tested without a socket.
// Not thread-safe: the transport serialises access.
//
// Every sentence is stamped on the mission clock. Navigation that arrives in a burst (a loaded
// backseat, a radio link that holds lines back) must not get one time for the whole burst: a
// turn needs strictly increasing times. So a sentence that carries a time (CPNVG, CPNVR, CPRBS,
// GPRMC, GPGGA) is stamped with it, mapped onto the mission clock by a SentenceClock (one for
// the frontseat's clock, one for the GPS receiver's, which need not agree). A sentence without
// one, or whose time is garbage, is stamped with its estimated arrival: a read's k-th of n lines
// arrived at prev + (now - prev) * k / n, spread between the previous read and this one. GPS
// fixes and speeds are aged against the navigation sample's stamp, on the same clock. Samples
// out of the session are strictly increasing in time, at least kMinNavStep_s apart: a sample
// whose stamp is not after the previous one's (a repeated or garbage time) is put just after it.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vehicle/local_grid.hpp"
#include "vehicle/marine_pid.hpp"
#include "vehicle/nmea.hpp"
#include "vehicle/sentence_clock.hpp"
#include "vehicle/thrust_mixing.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::vehicle {

struct M200Config {
  std::string id = "m200";
  // The local grid's origin; the emulator's default is the same (MIT Sailing Pavilion, the
  // MOOS-IvP Charles River datum).
  LatLon datum{42.358456, -71.087589};
  // Thesis Table 3.1: the gains the thesis ran the M200 with in the water.
  MarinePidConfig pid = MarinePidConfig::m200_in_water();
  MixConfig mix{};
  double controller_hz = 10.0;  // $PYDIR rate (iM200 on the thesis' vehicles)
  // The backseat sends all stop when the helm's newest command, or the newest navigation, is
  // older than this (the frontseat's own watchdog is 1.0 s on $PYDIR).
  double command_stale_s = 1.5;
  double nav_stale_s = 1.5;
  // The Vehicle interface's link rule: navigation older than this is a stale link.
  double link_stale_limit_s = 2.0;
  // A GPS fix or speed older than this is not combined with a newer heading.
  double fix_max_age_s = 1.0;
  double max_speed_mps = 1.7;  // the M200's rated speed
  double length_m = 1.35;
};

// What the mission and the store know of the vehicle a config drives.
VehicleInfo m200_info(const M200Config& config);

// Why the last $PYDIR was all stop, when it was.
enum class Failsafe { none, stopped, no_command, command_stale, no_nav, nav_stale };
const char* to_string(Failsafe f);

struct M200Battery {
  double t_s = 0.0;
  double stack_v = 0.0;
  double min_v = 0.0;
  double max_v = 0.0;
  double temperature_c = 0.0;
};

struct M200Counters {
  std::uint64_t lines = 0;
  std::uint64_t sentences = 0;  // parsed
  std::uint64_t errors = 0;     // lines that did not parse
  std::map<std::string, std::uint64_t> errors_by_code;
  std::string last_error;  // the newest parse error's message
  std::uint64_t lower_case_checksums = 0;
  std::uint64_t unknown_sentences = 0;  // well formed, of a type not used
  std::uint64_t nav_samples = 0;
  std::uint64_t nav_without_position = 0;  // CPNVG with no usable position anywhere
  // Sentence times far from the clock's (SentenceClock): stamped with the arrival instead.
  std::uint64_t sentence_times_rejected = 0;
  std::uint64_t pydir_sent = 0;
  std::uint64_t failsafe_stops = 0;  // $PYDIR 0,0 sent because of stale commands or navigation
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;
};

// The least time between two navigation samples out of a session.
inline constexpr double kMinNavStep_s = 1e-3;

class M200Session {
 public:
  // A line longer than this without a newline is hostile or garbage: on_received counts it as
  // oversized and skips it up to its newline rather than buffering it.
  static constexpr std::size_t kMaxBufferedLine = 1024;

  // Throws std::invalid_argument for a datum off the earth or rates that are not positive.
  explicit M200Session(M200Config config);

  const M200Config& config() const { return config_; }
  const VehicleInfo& info() const { return info_; }

  // The bytes one read from the link returned, at now_s on the mission clock: split into lines
  // here (a partial last line waits for the next read), and the read's lines stamped together.
  // Whatever the bytes, it never throws: a line that does not parse is counted with its error.
  void on_received(std::string_view bytes, double now_s);
  // One line from the frontseat, read alone at now_s.
  void on_line(std::string_view line, double now_s);

  // The sentence to send at a controller tick (with its CRLF), or empty when not connected.
  std::string control_tick(double now_s);

  void on_connected(double now_s);
  void on_disconnected(double now_s);
  bool connected() const { return connected_; }

  // The Vehicle interface, served by the transport.
  std::vector<NavSample> take_nav();
  std::optional<NavSample> last_nav() const { return last_nav_; }
  LinkState link_state(double now_s) const;
  void command(const DesiredCommand& desired);  // throws std::invalid_argument when not finite
  void all_stop(double now_s);
  std::optional<DesiredCommand> last_command() const { return desired_; }
  std::optional<ActuatorCommand> last_actuators() const { return actuators_; }

  std::optional<M200Battery> battery() const { return battery_; }
  Failsafe failsafe() const { return failsafe_; }
  const M200Counters& counters() const { return counters_; }

 private:
  struct Fix {
    double t_s;  // the sentence's stamp
    double x_m, y_m, lat_deg, lon_deg;
  };
  struct Stamped {
    double t_s;  // the sentence's stamp
    double value;
  };
  void on_lines(const std::vector<std::string_view>& lines, double now_s);
  void on_sentence(const NmeaSentence& sentence, double t_s);
  void on_cpnvg(const Cpnvg& s, double t_s);
  void forget_link();
  std::string send_stop(Failsafe why);

  M200Config config_;
  VehicleInfo info_;
  LocalGrid grid_;
  MarinePid pid_;
  bool connected_ = false;
  bool stopped_ = false;
  SentenceClock frontseat_clock_;
  SentenceClock gps_clock_;
  double previous_read_s_ = 0.0;
  std::string partial_;  // the start of a line the next read completes
  bool discarding_ = false;
  std::optional<Fix> gps_fix_;
  std::optional<Stamped> speed_mps_;
  std::optional<Stamped> yaw_rate_dps_;
  std::vector<NavSample> mailbox_;
  std::optional<NavSample> last_nav_;
  std::optional<DesiredCommand> desired_;
  std::optional<ActuatorCommand> actuators_;
  std::optional<M200Battery> battery_;
  Failsafe failsafe_ = Failsafe::none;
  M200Counters counters_;
};

}  // namespace avk::vehicle
