#pragma once
// The channels the station offers to Foxglove-speaking tools, live (the foxglove.websocket.v1
// connection) and recorded (a mission's MCAP file): one set per vehicle, JSON messages with
// JSON Schema. Where Foxglove has a well-known schema the channel uses it, so its 3D, Map, Plot
// and Log panels draw the data without configuration (docs/foxglove.md).

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avk::app::foxglove {

// The frame of the local grid: x east, y north, z up (metres from the datum). Foxglove's frames
// are right-handed with yaw counter-clockwise about z, so a heading (clockwise from north) is the
// yaw 90 deg - heading.
inline constexpr const char* kGridFrame = "grid";
inline constexpr const char* kMessageEncoding = "json";
inline constexpr const char* kSchemaEncoding = "jsonschema";
// The station's own schemas are named here; Foxglove's carry its names (foxglove.PoseInFrame ...).
inline constexpr const char* kNavigationSchemaName = "avk.Navigation";
inline constexpr const char* kTurnRecordSchemaName = "avk.TurnRecord";

enum class ChannelKind {
  pose,        // foxglove.PoseInFrame: the vehicle in the grid
  transform,   // foxglove.FrameTransform: grid -> the vehicle's frame
  location,    // foxglove.LocationFix: latitude/longitude, when the navigation has them
  navigation,  // avk.Navigation: flat numbers for the Plot panel
  turn,        // foxglove.SceneUpdate: the turn in progress, its predictions, the CKT cell
  region,      // foxglove.SceneUpdate: the operating region and its buffer
  log,         // foxglove.Log: mission and station events
  turn_record  // avk.TurnRecord: a finished turn as stored (raw and normalised); recordings only
};
inline constexpr std::array kLiveChannelKinds = {
    ChannelKind::pose, ChannelKind::transform, ChannelKind::location, ChannelKind::navigation,
    ChannelKind::turn, ChannelKind::region,    ChannelKind::log};
const char* to_string(ChannelKind k);

struct ChannelSpec {
  ChannelKind kind = ChannelKind::pose;
  std::string topic;        // "/<vehicle id>/pose"
  std::string schema_name;  // "foxglove.PoseInFrame", "avk.Navigation"
  std::string_view schema;  // JSON Schema text
  // Live delivery: a newer message replaces an unsent older one (telemetry, and scenes that carry
  // their whole state); otherwise every message is delivered (events).
  bool latest_value_wins = true;
  // A client that subscribes later receives the channel's last message at once (the region, the
  // turn being flown), as a latched ROS topic would.
  bool latched = false;
};

std::string topic(const std::string& vehicle_id, ChannelKind k);
// The vehicle's own frame (its pose's child frame): "<vehicle id>".
std::string vehicle_frame(const std::string& vehicle_id);
ChannelSpec channel_spec(const std::string& vehicle_id, ChannelKind k);
std::vector<ChannelSpec> live_channels(const std::string& vehicle_id);
// The channel a topic names, for a reader of a recording; none for another topic.
std::optional<ChannelKind> channel_kind_of(std::string_view topic, const std::string& vehicle_id);

}  // namespace avk::app::foxglove
