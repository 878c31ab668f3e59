#include "vehicle/gpsd_ais.hpp"

#include <gps.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string_view>

#include "vehicle/ais_fields.hpp"

namespace avk::vehicle {

namespace {

// How long one wait for gpsd's next line lasts: the bound on how late stop() is noticed.
constexpr int kWaitMicroseconds = 200000;

double system_clock_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

template <std::size_t N>
std::optional<std::string> text_field(const char (&field)[N]) {
  return ais_text(std::string_view(field, ::strnlen(field, N)));
}

// The position fields that types 1-3, 18 and 19 share, in libgps's unscaled units.
template <typename Fields>
void read_position(const Fields& f, AisReport& r) {
  r.lat_deg = ais_lat_deg(f.lat);
  r.lon_deg = ais_lon_deg(f.lon);
  if (!r.lat_deg || !r.lon_deg) {
    r.lat_deg.reset();
    r.lon_deg.reset();
  } else {
    r.position_accuracy_high = f.accuracy;
  }
  r.speed_mps = ais_speed_mps(f.speed);
  r.course_deg = ais_course_deg(f.course);
  r.heading_deg = ais_heading_deg(f.heading);
}

// Types gpsd decodes but that say nothing about a vessel's motion or name (base stations, binary
// messages, aids to navigation, ...) give no report.
std::optional<AisReport> to_report(const struct ais_t& ais, double received_s) {
  AisReport r;
  r.mmsi = ais.mmsi;
  r.message_type = static_cast<int>(ais.type);
  r.received_s = received_s;
  switch (ais.type) {
    case 1:
    case 2:
    case 3:
      read_position(ais.type1, r);
      r.nav_status = ais_nav_status(ais.type1.status);
      return r;
    case 18:
      read_position(ais.type18, r);
      return r;
    case 19:
      read_position(ais.type19, r);
      r.name = text_field(ais.type19.shipname);
      r.ship_type = ais_ship_type(ais.type19.shiptype);
      return r;
    case 5:
      r.name = text_field(ais.type5.shipname);
      r.callsign = text_field(ais.type5.callsign);
      r.ship_type = ais_ship_type(ais.type5.shiptype);
      return r;
    case 24:
      // gpsd pairs part A (the name) with part B (type, call sign) and sends both as one report;
      // a part it could not pair comes alone.
      if (ais.type24.part != ais.type24.part_b) r.name = text_field(ais.type24.shipname);
      if (ais.type24.part != ais.type24.part_a) {
        r.callsign = text_field(ais.type24.callsign);
        r.ship_type = ais_ship_type(ais.type24.shiptype);
      }
      return r;
    default:
      return std::nullopt;
  }
}

}  // namespace

GpsdAis::GpsdAis(GpsdAisOptions options, ReportHandler on_report, LinkHandler on_link)
    : options_(std::move(options)), on_report_(std::move(on_report)), on_link_(std::move(on_link)) {
  if (!options_.clock) options_.clock = system_clock_s;
}

GpsdAis::~GpsdAis() {
  stop();
}

void GpsdAis::start() {
  if (thread_.joinable()) return;
  stopping_ = false;
  thread_ = std::thread([this] { run(); });
}

void GpsdAis::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool GpsdAis::pause(double seconds) {
  std::unique_lock lock(mutex_);
  return !wake_.wait_for(lock, std::chrono::duration<double>(seconds),
                         [this] { return stopping_.load(); });
}

void GpsdAis::run() {
  double backoff_s = options_.min_backoff_s;
  while (!stopping_) {
    struct gps_data_t data;
    std::memset(&data, 0, sizeof data);
    if (gps_open(options_.host.c_str(), options_.port.c_str(), &data) != 0) {
      if (!pause(backoff_s)) break;
      backoff_s = std::min(backoff_s * 2.0, options_.max_backoff_s);
      continue;
    }
    if (gps_stream(&data, WATCH_ENABLE | WATCH_JSON, nullptr) != 0) {
      gps_close(&data);
      if (!pause(backoff_s)) break;
      backoff_s = std::min(backoff_s * 2.0, options_.max_backoff_s);
      continue;
    }
    backoff_s = options_.min_backoff_s;
    if (on_link_) on_link_(true);
    while (!stopping_) {
      if (!gps_waiting(&data, kWaitMicroseconds)) {
        // A timeout leaves errno alone; a failed select on the socket does not.
        if (errno != 0 && errno != EINTR && errno != EAGAIN) break;
        continue;
      }
      errno = 0;
      data.set = 0;
      if (gps_read(&data, nullptr, 0) == -1) break;  // gpsd closed the socket, or a read error
      if ((data.set & AIS_SET) == 0) continue;
      if (const auto report = to_report(data.ais, options_.clock())) on_report_(*report);
    }
    gps_close(&data);
    if (on_link_) on_link_(false);
    if (!stopping_ && !pause(backoff_s)) break;
  }
}

}  // namespace avk::vehicle
