#include "vehicle/vehicle.hpp"

#include <cmath>
#include <stdexcept>

#include "kinematics/angles.hpp"
#include "kinematics/text_limit.hpp"

namespace avk::vehicle {

std::optional<std::string> vehicle_id_problem(std::string_view id) {
  if (id.empty()) return "must not be empty";
  if (auto why = kinematics::text_too_long(id, kMaxVehicleIdBytes)) return why;
  for (const char c : id)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return std::string("must not hold control characters");
  return std::nullopt;
}

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

std::optional<LinkState> link_state_from_string(std::string_view s) {
  for (const LinkState l : all_link_states())
    if (s == to_string(l)) return l;
  return std::nullopt;
}

const std::vector<LinkState>& all_link_states() {
  // to_string's switch is checked to name every enumerator (0..n-1), and answers "?" past them.
  static const std::vector<LinkState> all = [] {
    std::vector<LinkState> out;
    for (int i = 0; std::string_view(to_string(static_cast<LinkState>(i))) != "?"; ++i)
      out.push_back(static_cast<LinkState>(i));
    return out;
  }();
  return all;
}

DesiredCommand checked_command(const DesiredCommand& desired) {
  if (!std::isfinite(desired.t_s) || !std::isfinite(desired.heading_deg) ||
      !std::isfinite(desired.speed_mps) || desired.speed_mps < 0.0) {
    throw std::invalid_argument("desired heading and speed must be finite, speed >= 0");
  }
  DesiredCommand d = desired;
  d.heading_deg = kinematics::wrap360_deg(desired.heading_deg);
  return d;
}

LinkState link_state_from(const std::optional<NavSample>& last, bool connected, double now_s,
                          double stale_limit_s) {
  if (!connected || !last) return LinkState::disconnected;
  return now_s - last->t_s > stale_limit_s ? LinkState::stale : LinkState::live;
}

}  // namespace avk::vehicle
