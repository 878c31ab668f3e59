#include "vehicle/vehicle.hpp"

namespace avk::vehicle {

const char* to_string(LinkState s) {
  switch (s) {
    case LinkState::live:
      return "LIVE";
    case LinkState::stale:
      return "STALE";
    case LinkState::disconnected:
      return "DISCONNECTED";
  }
  return "?";
}

LinkState link_state_from(const std::optional<NavSample>& last, bool connected, double now_s,
                          double stale_limit_s) {
  if (!connected || !last) return LinkState::disconnected;
  return now_s - last->t_s > stale_limit_s ? LinkState::stale : LinkState::live;
}

}  // namespace avk::vehicle
