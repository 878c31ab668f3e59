#include "vehicle/m200_session.hpp"

#include "vehicle/nav_ranges.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace avk::vehicle {

const char* to_string(Failsafe f) {
  switch (f) {
    case Failsafe::none:
      return "none";
    case Failsafe::stopped:
      return "stopped";
    case Failsafe::no_command:
      return "no_command";
    case Failsafe::command_stale:
      return "command_stale";
    case Failsafe::no_nav:
      return "no_nav";
    case Failsafe::nav_stale:
      return "nav_stale";
  }
  return "?";
}

M200Session::M200Session(M200Config config)
    : config_(std::move(config)),
      grid_(config_.datum.lat_deg, config_.datum.lon_deg),
      pid_(config_.pid) {
  if (!(config_.controller_hz > 0.0) || !(config_.command_stale_s > 0.0) ||
      !(config_.nav_stale_s > 0.0) || !(config_.link_stale_limit_s > 0.0) ||
      !(config_.fix_max_age_s > 0.0)) {
    throw std::invalid_argument("M200 rates and stale limits must be positive");
  }
  info_ = m200_info(config_);
}

VehicleInfo m200_info(const M200Config& config) {
  return {config.id, "m200", config.max_speed_mps, config.length_m};
}

namespace {

enum class TimeSource { none, frontseat, gps };

struct SentenceTime {
  TimeSource source = TimeSource::none;
  double time_of_day_s = 0.0;
};

// The time a sentence carries, and whose clock it is on. The other sentence types the driver
// uses none of, so their times do not steer its clock.
SentenceTime time_of(const NmeaSentence& sentence) {
  return std::visit(
      [](const auto& s) -> SentenceTime {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Cpnvg> || std::is_same_v<T, Cpnvr> ||
                      std::is_same_v<T, Cprbs>) {
          return {TimeSource::frontseat, s.time_s};
        } else if constexpr (std::is_same_v<T, Gprmc> || std::is_same_v<T, Gpgga>) {
          if (s.time_s) return {TimeSource::gps, *s.time_s};
          return {};
        } else {
          return {};
        }
      },
      sentence);
}

}  // namespace

void M200Session::on_received(std::string_view bytes, double now_s) {
  std::vector<std::string> lines;
  for (const char c : bytes) {
    if (c == '\n') {
      if (!discarding_) lines.push_back(std::move(partial_));
      partial_.clear();
      discarding_ = false;
    } else if (!discarding_) {
      partial_.push_back(c);
      if (partial_.size() > kMaxBufferedLine) {
        lines.push_back(std::move(partial_));  // the parser counts it as oversized
        partial_.clear();
        discarding_ = true;
      }
    }
  }
  on_lines(std::vector<std::string_view>(lines.begin(), lines.end()), now_s);
}

void M200Session::on_line(std::string_view line, double now_s) {
  on_lines({line}, now_s);
}

void M200Session::on_lines(const std::vector<std::string_view>& lines, double now_s) {
  if (lines.empty()) return;
  // The read's lines came in at some time since the previous read: without a time of their
  // own, the k-th of n is put k/n of the way from that read to this one.
  const double from_s = std::min(previous_read_s_, now_s);
  previous_read_s_ = now_s;
  struct Read {
    NmeaSentence sentence;
    double arrival_s;
    SentenceTime time;
    bool time_ok = false;
  };
  std::vector<Read> read;
  read.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    ++counters_.lines;
    NmeaParseResult r = parse_sentence(lines[i], NmeaDirection::frontseat_to_backseat);
    if (const NmeaError* e = r.error()) {
      ++counters_.errors;
      ++counters_.errors_by_code[to_string(e->code)];
      counters_.last_error = e->message;
      continue;
    }
    ++counters_.sentences;
    if (r.checksum == NmeaChecksum::lower_case) ++counters_.lower_case_checksums;
    const double arrival_s =
        from_s + (now_s - from_s) * static_cast<double>(i + 1) / static_cast<double>(lines.size());
    NmeaSentence& sentence = std::get<NmeaSentence>(r.value);
    const SentenceTime time = time_of(sentence);
    read.push_back({std::move(sentence), arrival_s, time});
  }
  const auto clock_for = [this](TimeSource source) -> SentenceClock* {
    if (source == TimeSource::frontseat) return &frontseat_clock_;
    if (source == TimeSource::gps) return &gps_clock_;
    return nullptr;
  };
  // Every time of the read is seen before any is mapped, so that the whole read is mapped with
  // one offset and its stamps keep the spacing of its sentence times.
  for (Read& r : read) {
    if (SentenceClock* clock = clock_for(r.time.source)) {
      r.time_ok = clock->observe(r.time.time_of_day_s, now_s);
      if (!r.time_ok) ++counters_.sentence_times_rejected;
    }
  }
  for (const Read& r : read) {
    const SentenceClock* clock = clock_for(r.time.source);
    on_sentence(r.sentence, r.time_ok ? clock->map(r.time.time_of_day_s, now_s) : r.arrival_s);
  }
}

void M200Session::on_sentence(const NmeaSentence& sentence, double t_s) {
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Cpnvg>) {
          on_cpnvg(s, t_s);
        } else if constexpr (std::is_same_v<T, Cpnvr>) {
          speed_mps_ = Stamped{t_s, std::hypot(s.v_east_mps, s.v_north_mps)};
          yaw_rate_dps_ = Stamped{t_s, s.yaw_rate_dps};
        } else if constexpr (std::is_same_v<T, Gprmc>) {
          if (!s.valid) return;
          if (s.lat_deg && s.lon_deg) {
            const GridPoint p = grid_.to_grid(*s.lat_deg, *s.lon_deg);
            gps_fix_ = Fix{t_s, p.x_m, p.y_m, *s.lat_deg, *s.lon_deg};
          }
          if (const auto v = s.speed_mps()) speed_mps_ = Stamped{t_s, *v};
        } else if constexpr (std::is_same_v<T, Gpgga>) {
          if (s.quality > 0 && s.lat_deg && s.lon_deg) {
            const GridPoint p = grid_.to_grid(*s.lat_deg, *s.lon_deg);
            gps_fix_ = Fix{t_s, p.x_m, p.y_m, *s.lat_deg, *s.lon_deg};
          }
        } else if constexpr (std::is_same_v<T, Gpvtg>) {
          if (const auto v = s.speed_mps()) speed_mps_ = Stamped{t_s, *v};
        } else if constexpr (std::is_same_v<T, Cprbs>) {
          battery_ = M200Battery{t_s, s.stack_v, s.min_v, s.max_v, s.temperature_c};
        } else {
          // Compass, IMU, CPALT, backseat sentences echoed back and unknown types carry
          // nothing the navigation solution needs.
          ++counters_.unknown_sentences;
        }
      },
      sentence);
}

void M200Session::on_cpnvg(const Cpnvg& s, double t_s) {
  // The heading is the frontseat's (CPNVG). Its position is used when it has GPS quality; else
  // a fresh GPRMC/GPGGA fix. Speed over ground comes from the newest GPRMC, GPVTG or CPNVR.
  // Freshness is judged on the sample's own stamp, the clock every sentence was stamped on.
  NavSample n;
  n.t_s = last_nav_ ? std::max(t_s, last_nav_->t_s + kMinNavStep_s) : t_s;
  n.heading_deg = s.heading_deg;
  const auto fresh = [&](double stamp_s) { return n.t_s - stamp_s <= config_.fix_max_age_s; };
  if (s.position_ok) {
    const GridPoint p = grid_.to_grid(s.lat_deg, s.lon_deg);
    n.x_m = p.x_m;
    n.y_m = p.y_m;
    n.lat_deg = s.lat_deg;
    n.lon_deg = s.lon_deg;
  } else if (gps_fix_ && fresh(gps_fix_->t_s)) {
    n.x_m = gps_fix_->x_m;
    n.y_m = gps_fix_->y_m;
    n.lat_deg = gps_fix_->lat_deg;
    n.lon_deg = gps_fix_->lon_deg;
  } else {
    ++counters_.nav_without_position;
    return;
  }
  if (speed_mps_ && fresh(speed_mps_->t_s)) {
    n.speed_mps = speed_mps_->value;
  } else if (last_nav_) {
    // No speed sentence: the track's own rate, as a last resort. A rate no boat makes is a
    // position jump (a fix after a dropout), not a speed: the last speed stands instead.
    const double rate_mps =
        std::hypot(n.x_m - last_nav_->x_m, n.y_m - last_nav_->y_m) / (n.t_s - last_nav_->t_s);
    n.speed_mps = kSpeedRange_mps.contains(rate_mps) ? rate_mps : last_nav_->speed_mps;
  }
  if (yaw_rate_dps_ && fresh(yaw_rate_dps_->t_s)) n.yaw_rate_dps = yaw_rate_dps_->value;
  ++counters_.nav_samples;
  last_nav_ = n;
  mailbox_.push_back(n);
  // A mission that never drains its mail must not grow the driver without bound.
  constexpr std::size_t kMailboxLimit = 100000;
  if (mailbox_.size() > kMailboxLimit) mailbox_.erase(mailbox_.begin());
}

std::string M200Session::send_stop(Failsafe why) {
  if (why != Failsafe::stopped && failsafe_ != why) ++counters_.failsafe_stops;
  failsafe_ = why;
  pid_.reset();  // nothing from before the stop may jolt the vehicle when it lifts
  ActuatorCommand a;
  a.left_pct = 0.0;
  a.right_pct = 0.0;
  actuators_ = a;
  ++counters_.pydir_sent;
  return format_pydir(0.0, 0.0);
}

std::string M200Session::control_tick(double now_s) {
  if (!connected_) return {};
  if (stopped_) return send_stop(Failsafe::stopped);
  if (!desired_) return send_stop(Failsafe::no_command);
  if (now_s - desired_->t_s > config_.command_stale_s) return send_stop(Failsafe::command_stale);
  if (!last_nav_) return send_stop(Failsafe::no_nav);
  if (now_s - last_nav_->t_s > config_.nav_stale_s) return send_stop(Failsafe::nav_stale);
  failsafe_ = Failsafe::none;
  ActuatorCommand a = pid_.step(now_s, last_nav_, desired_);
  const DifferentialThrust lr = mix_differential(a.rudder_pct, a.thrust_pct, config_.mix);
  a.left_pct = lr.left_pct;
  a.right_pct = lr.right_pct;
  actuators_ = a;
  ++counters_.pydir_sent;
  return format_pydir(lr.left_pct, lr.right_pct);
}

void M200Session::on_connected(double now_s) {
  forget_link();
  previous_read_s_ = now_s;
  connected_ = true;
  ++counters_.connects;
}

void M200Session::on_disconnected(double) {
  if (!connected_) return;
  connected_ = false;
  ++counters_.disconnects;
  forget_link();
}

void M200Session::forget_link() {
  // Partial state from the old link must not be combined with the new one's, and the new link
  // may reach a frontseat whose clock is another.
  gps_fix_.reset();
  speed_mps_.reset();
  yaw_rate_dps_.reset();
  pid_.reset();
  frontseat_clock_.reset();
  gps_clock_.reset();
  partial_.clear();
  discarding_ = false;
}

std::vector<NavSample> M200Session::take_nav() {
  std::vector<NavSample> out;
  out.swap(mailbox_);
  return out;
}

LinkState M200Session::link_state(double now_s) const {
  return link_state_from(last_nav_, connected_, now_s, config_.link_stale_limit_s);
}

void M200Session::command(const DesiredCommand& desired) {
  desired_ = checked_command(desired);
  stopped_ = false;
}

void M200Session::all_stop(double now_s) {
  stopped_ = true;
  desired_ = DesiredCommand{now_s, desired_ ? desired_->heading_deg : 0.0, 0.0};
}

}  // namespace avk::vehicle
