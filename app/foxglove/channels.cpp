#include "app/foxglove/channels.hpp"

#include <stdexcept>

#include "app/foxglove/schemas.hpp"

namespace avk::app::foxglove {

namespace {

// Every number the Plot panel plots is a plain member; a value the vehicle does not report is
// null rather than absent, so a plot path never silently points at nothing.
constexpr std::string_view kNavigationSchema = R"json({
  "title": "avk.Navigation",
  "description": "One navigation report of the vehicle with the helm's command in force (AVK Station). Local grid: x east, y north, metres; headings in degrees clockwise from north.",
  "type": "object",
  "properties": {
    "timestamp": {"type": "object", "properties": {"sec": {"type": "integer", "minimum": 0}, "nsec": {"type": "integer", "minimum": 0, "maximum": 999999999}}, "required": ["sec", "nsec"]},
    "t_s": {"type": "number", "description": "station clock, seconds"},
    "x_m": {"type": "number"},
    "y_m": {"type": "number"},
    "heading_deg": {"type": "number"},
    "desired_heading_deg": {"type": ["number", "null"]},
    "speed_mps": {"type": "number"},
    "desired_speed_mps": {"type": ["number", "null"]},
    "yaw_rate_dps": {"type": ["number", "null"], "description": "+ clockwise"},
    "helm_mode": {"type": ["string", "null"]},
    "mission_id": {"type": ["integer", "null"]}
  },
  "required": ["timestamp", "t_s", "x_m", "y_m", "heading_deg", "desired_heading_deg", "speed_mps", "desired_speed_mps", "yaw_rate_dps", "helm_mode", "mission_id"]
})json";

// A stored turn as the station's turn record (docs/turn-record-format.md) with its stored row:
// what an import needs to rebuild the turn exactly.
constexpr std::string_view kTurnRecordSchema = R"json({
  "title": "avk.TurnRecord",
  "description": "A finished turn of a collection mission as AVK Station stores it: the row's summary, the raw TurnSequence and its normalised form (turn JSON).",
  "type": "object",
  "properties": {
    "id": {"type": "integer"},
    "status": {"type": "string"},
    "reason": {"type": "string"},
    "raw": {"type": "object"},
    "normalized": {"type": ["object", "null"]}
  },
  "required": ["id", "status", "raw", "normalized"]
})json";

std::string_view well_known(const char* name) {
  const auto s = well_known_schema(name);
  if (!s) throw std::logic_error(std::string("no vendored schema ") + name);
  return *s;
}

}  // namespace

const char* to_string(ChannelKind k) {
  switch (k) {
    case ChannelKind::pose:
      return "pose";
    case ChannelKind::transform:
      return "tf";
    case ChannelKind::location:
      return "location";
    case ChannelKind::navigation:
      return "navigation";
    case ChannelKind::turn:
      return "turn";
    case ChannelKind::region:
      return "region";
    case ChannelKind::log:
      return "log";
    case ChannelKind::turn_record:
      return "turn_record";
  }
  return "?";
}

std::string topic(const std::string& vehicle_id, ChannelKind k) {
  return "/" + vehicle_id + "/" + to_string(k);
}

std::string vehicle_frame(const std::string& vehicle_id) {
  return vehicle_id;
}

ChannelSpec channel_spec(const std::string& vehicle_id, ChannelKind k) {
  ChannelSpec s;
  s.kind = k;
  s.topic = topic(vehicle_id, k);
  switch (k) {
    case ChannelKind::pose:
      s.schema_name = "foxglove.PoseInFrame";
      break;
    case ChannelKind::transform:
      s.schema_name = "foxglove.FrameTransform";
      break;
    case ChannelKind::location:
      s.schema_name = "foxglove.LocationFix";
      break;
    case ChannelKind::navigation:
      s.schema_name = kNavigationSchemaName;
      s.schema = kNavigationSchema;
      break;
    case ChannelKind::turn:
      s.schema_name = "foxglove.SceneUpdate";
      s.latched = true;
      break;
    case ChannelKind::region:
      s.schema_name = "foxglove.SceneUpdate";
      s.latched = true;
      break;
    case ChannelKind::log:
      s.schema_name = "foxglove.Log";
      s.latest_value_wins = false;
      break;
    case ChannelKind::turn_record:
      s.schema_name = kTurnRecordSchemaName;
      s.schema = kTurnRecordSchema;
      s.latest_value_wins = false;
      break;
  }
  if (s.schema.empty()) s.schema = well_known(s.schema_name.c_str());
  return s;
}

std::vector<ChannelSpec> live_channels(const std::string& vehicle_id) {
  std::vector<ChannelSpec> out;
  for (const auto k : kLiveChannelKinds)
    out.push_back(channel_spec(vehicle_id, k));
  return out;
}

std::optional<ChannelKind> channel_kind_of(std::string_view t, const std::string& vehicle_id) {
  for (const auto k :
       {ChannelKind::pose, ChannelKind::transform, ChannelKind::location, ChannelKind::navigation,
        ChannelKind::turn, ChannelKind::region, ChannelKind::log, ChannelKind::turn_record})
    if (t == topic(vehicle_id, k)) return k;
  return std::nullopt;
}

}  // namespace avk::app::foxglove
