#pragma once
// The traffic around the vehicle as AIS reports it (docs/ais.md): a table by MMSI that merges
// position reports with static data (names come in other messages, minutes apart), places them on
// the local grid about the mission's datum, and forgets a vessel that has stopped reporting.
// Thread-safe: the gpsd client's thread updates it while others take snapshots.
//
// Aging follows the reporting intervals of ITU-R M.1371: a Class A vessel under way reports every
// 2 to 10 s, a Class B one every 30 s, but at anchor, moored or slow (at or under 3 kn) only every
// 3 minutes. A moving contact unheard for max_age_s (3 minutes) is gone; a slow one, or one of
// unknown speed, is kept for slow_max_age_s (10 minutes: three missed 3-minute reports). Static
// data (sent every 6 minutes) is kept for static_max_age_s so that a name outlives gaps in the
// position reports.

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/ais_contact_view.hpp"
#include "kinematics/maneuver.hpp"
#include "vehicle/ais_report.hpp"
#include "vehicle/local_grid.hpp"
#include "vehicle/nmea.hpp"

namespace avk::app {

struct AisContactsOptions {
  double max_age_s = 180.0;
  double slow_max_age_s = 600.0;
  double slow_speed_mps = 3.0 * vehicle::kMetresPerSecondPerKnot;
  double static_max_age_s = 1800.0;
};

class AisContacts {
 public:
  // now_s: the clock of the reports' received_s (GpsdAisOptions::clock), read for ages.
  AisContacts(vehicle::LatLon datum, std::function<double()> now_s,
              AisContactsOptions options = {});

  // A report without a position or static data changes nothing; one that does refreshes the
  // contact's entry. Contacts past their age are dropped here.
  void update(const vehicle::AisReport& report);
  // The contacts with a position not past their age, by MMSI.
  std::vector<AisContactView> snapshot() const;
  // Entries held (with or without a position), for the tests of aging.
  std::size_t size() const;

 private:
  struct Entry {
    std::optional<vehicle::AisReport> position;  // the last report with one
    std::optional<double> static_received_s;
    std::string name;
    std::string callsign;
    std::optional<int> ship_type;
  };
  bool position_current(const Entry& e, double now_s) const;
  void prune(double now_s);

  vehicle::LocalGrid grid_;
  std::function<double()> now_s_;
  AisContactsOptions options_;
  mutable std::mutex mutex_;
  std::map<std::uint32_t, Entry> entries_;
};

// A contact for the maneuver and encounter predictions, at its position dead-reckoned to the
// snapshot's time (age_s at its course and speed). nullopt without a speed over ground. Without a
// course it is given course 0 and a course spread of 180 degrees.
std::optional<kinematics::Contact> to_kinematics_contact(const AisContactView& c);

}  // namespace avk::app
