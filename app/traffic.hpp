#pragma once
// The traffic around the station's vehicles as the station knows it now: the AIS contacts it
// watches through gpsd (app/traffic_watch.hpp), if it was started with a source.

#include <string>
#include <vector>

#include "app/ais_contact_view.hpp"

namespace avk::app {

class Context;

struct TrafficView {
  bool watching = false;                 // the station has a traffic source
  std::string source;                    // "gpsd HOST:PORT"
  bool link_up = false;                  // gpsd is connected now
  std::vector<AisContactView> contacts;  // by MMSI, with a position not past its age
};

// Never fails: a station without a traffic source answers watching = false and no contacts.
TrafficView traffic(Context& ctx);

}  // namespace avk::app
