#include "app/ais_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avk::app {

namespace {

// The position accuracy flag of ITU-R M.1371 says only "better than 10 m" (1, DGNSS) or "worse"
// (0, plain GNSS, or not known). 10 m is taken as the 1-sigma spread of the first; 100 m of the
// second covers plain GNSS plus the offset of the antenna from the hull's centre on a large ship
// (AIS reports the antenna's position), a deliberately cautious choice.
constexpr double kHighAccuracySd_m = 10.0;
constexpr double kLowAccuracySd_m = 100.0;
// Speed is sent in 0.1 kn and course in 0.1 degree, but both come from the vessel's GNSS over
// ground, which scatters far more than that: 0.25 m/s and 5 degrees, 1 sigma, are chosen to cover
// a small vessel's speed and course noise at a few knots.
constexpr double kSpeedSd_mps = 0.25;
constexpr double kCourseSd_deg = 5.0;
constexpr double kUnknownCourseSd_deg = 180.0;

}  // namespace

AisContacts::AisContacts(vehicle::LatLon datum, std::function<double()> now_s,
                         AisContactsOptions options)
    : grid_(datum.lat_deg, datum.lon_deg), now_s_(std::move(now_s)), options_(options) {}

bool AisContacts::position_current(const Entry& e, double now_s) const {
  if (!e.position) return false;
  const auto& p = *e.position;
  const bool slow = !p.speed_mps || *p.speed_mps <= options_.slow_speed_mps;
  return now_s - p.received_s <= (slow ? options_.slow_max_age_s : options_.max_age_s);
}

void AisContacts::prune(double now_s) {
  for (auto it = entries_.begin(); it != entries_.end();) {
    Entry& e = it->second;
    if (e.position && !position_current(e, now_s)) e.position.reset();
    if (e.static_received_s && now_s - *e.static_received_s > options_.static_max_age_s) {
      e.static_received_s.reset();
      e.name.clear();
      e.callsign.clear();
      e.ship_type.reset();
    }
    it = (!e.position && !e.static_received_s) ? entries_.erase(it) : std::next(it);
  }
}

void AisContacts::update(const vehicle::AisReport& report) {
  // Positions the grid cannot take (off the earth, not finite) are not positions.
  const bool has_position = report.lat_deg && report.lon_deg && std::isfinite(*report.lat_deg) &&
                            std::isfinite(*report.lon_deg) && std::abs(*report.lat_deg) <= 90.0;
  const bool has_static = report.name || report.callsign || report.ship_type;
  const double now = now_s_();
  std::lock_guard lock(mutex_);
  if (report.mmsi != 0 && (has_position || has_static)) {
    Entry& e = entries_[report.mmsi];
    if (has_position) e.position = report;
    if (has_static) {
      e.static_received_s = report.received_s;
      if (report.name) e.name = *report.name;
      if (report.callsign) e.callsign = *report.callsign;
      if (report.ship_type) e.ship_type = report.ship_type;
    }
  }
  prune(now);
}

std::vector<AisContactView> AisContacts::snapshot() const {
  const double now = now_s_();
  std::lock_guard lock(mutex_);
  std::vector<AisContactView> out;
  for (const auto& [mmsi, e] : entries_) {
    if (!position_current(e, now)) continue;
    const auto& p = *e.position;
    AisContactView v;
    v.mmsi = mmsi;
    v.name = e.name;
    v.callsign = e.callsign;
    v.ship_type = e.ship_type;
    v.lat_deg = *p.lat_deg;
    v.lon_deg = *p.lon_deg;
    const vehicle::GridPoint g = grid_.to_grid(v.lat_deg, v.lon_deg);
    v.x_m = g.x_m;
    v.y_m = g.y_m;
    v.course_deg = p.course_deg;
    v.speed_mps = p.speed_mps;
    v.heading_deg = p.heading_deg;
    v.position_accuracy_high = p.position_accuracy_high.value_or(false);
    v.age_s = std::max(0.0, now - p.received_s);
    out.push_back(std::move(v));
  }
  return out;
}

std::size_t AisContacts::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

std::optional<kinematics::Contact> to_kinematics_contact(const AisContactView& c) {
  if (!c.speed_mps) return std::nullopt;
  kinematics::Contact k;
  k.speed_mps = *c.speed_mps;
  k.course_deg = c.course_deg.value_or(0.0);
  const double run_m = c.course_deg ? k.speed_mps * c.age_s : 0.0;
  const double rad = k.course_deg * std::numbers::pi / 180.0;
  k.x_m = c.x_m + run_m * std::sin(rad);
  k.y_m = c.y_m + run_m * std::cos(rad);
  k.position_sd_m = c.position_accuracy_high ? kHighAccuracySd_m : kLowAccuracySd_m;
  k.speed_sd_mps = kSpeedSd_mps;
  k.course_sd_deg = c.course_deg ? kCourseSd_deg : kUnknownCourseSd_deg;
  return k;
}

}  // namespace avk::app
