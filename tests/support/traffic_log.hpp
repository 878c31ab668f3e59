#pragma once
// A traffic scenario's vessels at one moment as a gpsfake log: their static data, then their
// positions (the order a receiver hears them in after it is switched on).

#include <string>

#include "sim/ais_traffic.hpp"

namespace avk::testing {

inline std::string traffic_log_at(const avk::sim::AisTraffic& traffic, double t_s) {
  std::string log;
  for (const auto& l : traffic.static_sentences())
    log += l;
  for (const auto& l : traffic.position_sentences(t_s))
    log += l;
  return log;
}

}  // namespace avk::testing
