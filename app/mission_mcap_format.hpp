#pragma once
// What a mission's MCAP file holds beside the Foxglove channels, shared by its export and its
// import: the names of its metadata records, how their numbers are written, and the yaw rate its
// navigation messages carry.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "kinematics/angles.hpp"
#include "store/store.hpp"

namespace avk::app {

inline constexpr const char* kMissionRecord = "avk.mission";
inline constexpr const char* kVehicleRecord = "avk.vehicle";
inline constexpr const char* kConditionSetsRecord = "avk.condition_sets";
inline constexpr const char* kCurrentRecord = "avk.current";

// Numbers in metadata records are JSON number text: shortest round-trip, so an import reads the
// same double back. An absent value is the empty string.
inline std::string number_text(double v) {
  return nlohmann::json(v).dump();
}
inline std::string number_text(const std::optional<double>& v) {
  return v ? number_text(*v) : std::string();
}

// Heading change over time from the previous sample, wrapped, + clockwise.
inline std::optional<double> yaw_rate_dps(const store::NavRow* previous, const store::NavRow& r) {
  if (!previous || !(r.t_s > previous->t_s)) return std::nullopt;
  return kinematics::angle180_deg(r.heading_deg - previous->heading_deg) / (r.t_s - previous->t_s);
}

}  // namespace avk::app
