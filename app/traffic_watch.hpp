#pragma once
// The traffic the station watches: AIS reports from gpsd (vehicle/gpsd_ais.hpp) kept in the
// contact table (app/ais_contacts.hpp) about the station's datum. Started and stopped with the
// station; while gpsd is away the table keeps what it had and ages it out (docs/ais.md).

#include <atomic>
#include <string>

#include "app/ais_contacts.hpp"
#include "app/traffic.hpp"
#include "vehicle/gpsd_ais.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::app {

struct TrafficOptions {
  vehicle::GpsdAisOptions gpsd;  // its clock, when set, also ages the contacts
  vehicle::LatLon datum;         // where the local grid lies: contacts are placed about it
  AisContactsOptions ages;
};

class TrafficWatch {
 public:
  explicit TrafficWatch(TrafficOptions options);
  ~TrafficWatch();
  TrafficWatch(const TrafficWatch&) = delete;
  TrafficWatch& operator=(const TrafficWatch&) = delete;

  void start();
  void stop();
  TrafficView view() const;

 private:
  std::string source_;
  std::function<double()> now_s_;
  AisContacts contacts_;
  std::atomic<bool> link_up_{false};
  vehicle::GpsdAis client_;
};

}  // namespace avk::app
