#include "app/mission_mcap.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/foxglove/channels.hpp"
#include "app/foxglove/messages.hpp"
#include "app/foxglove_scene.hpp"
#include "app/imported_text.hpp"
#include "app/mcap/reader.hpp"
#include "app/mission_legs.hpp"
#include "app/mission_mcap_format.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/turn_json.hpp"
#include "mission/event_kind.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/nav_ranges.hpp"

#ifndef AVK_STATION_VERSION
#define AVK_STATION_VERSION ""
#endif

namespace avk::app {

namespace {

using nlohmann::json;
namespace fg = foxglove;
namespace kin = kinematics;

// Everything of a mission the file carries but its navigation and its turns' samples, which are
// read from the store as they are written: a mission of a day at 10 Hz holds close to a million
// navigation samples, and the export must not hold them (or every turn) whole.
struct MissionData {
  store::Mission mission;
  vehicle::VehicleInfo vehicle;
  std::vector<store::MissionEvent> events;
  std::vector<store::TurnRow> turns;  // by id
  std::vector<store::ConditionSetTiming> condition_sets;
  std::optional<store::StoredCurrent> current;
  std::size_t nav_samples = 0;  // counted as they are written
};

MissionData load_mission(store::Store& db, const store::Mission& m) {
  MissionData d;
  d.mission = m;
  d.vehicle = db.vehicles()
                  .get(m.vehicle_id)
                  .value_or(vehicle::VehicleInfo{m.vehicle_id, "", 0.0, std::nullopt});
  constexpr int kPage = 1000;
  for (std::int64_t after = 0;;) {
    auto page = db.missions().events(m.id, after, kPage);
    if (page.empty()) break;
    after = page.back().id;
    d.events.insert(d.events.end(), page.begin(), page.end());
  }
  for_each_mission_turn(db, m.id, std::nullopt,
                        [&](const store::TurnRow& t) { d.turns.push_back(t); });
  d.condition_sets = db.missions().condition_sets(m.id);
  d.current = db.currents().for_mission(m.id);
  return d;
}

json optional_json(const std::optional<double>& v) {
  return v ? json(*v) : json();
}

// ---------------------------------------------------------------------------------------------
// Export

std::map<std::string, std::string> mission_entries(const MissionData& d) {
  const store::Mission& m = d.mission;
  return {{"avk_mcap_version", kMissionMcapVersion},
          {"id", std::to_string(m.id)},
          {"vehicle_id", m.vehicle_id},
          {"name", m.name},
          {"config_json", m.config_json},
          {"status", store::to_string(m.status)},
          {"status_reason", m.status_reason},
          {"created_utc", m.created_utc},
          {"started_s", number_text(m.started_s)},
          {"ended_s", number_text(m.ended_s)},
          {"nav_samples", std::to_string(d.nav_samples)},
          {"events", std::to_string(d.events.size())},
          {"turns", std::to_string(d.turns.size())}};
}

std::map<std::string, std::string> vehicle_entries(const vehicle::VehicleInfo& v) {
  return {{"id", v.id},
          {"kind", v.kind},
          {"max_speed_mps", number_text(v.max_speed_mps)},
          {"length_m", number_text(v.length_m)}};
}

std::map<std::string, std::string> condition_set_entries(
    const std::vector<store::ConditionSetTiming>& sets) {
  json a = json::array();
  for (const auto& c : sets)
    a.push_back({{"start_s", c.start_s},
                 {"end_s", c.end_s},
                 {"target_speed_mps", c.target_speed_mps},
                 {"outcome", c.outcome}});
  return {{"json", a.dump()}};
}

std::map<std::string, std::string> current_entries(const store::StoredCurrent& c) {
  const kin::CurrentEstimate& e = c.estimate;
  std::map<std::string, std::string> out = {{"t_s", number_text(c.t_s)},
                                            {"method", c.method},
                                            {"east_mps", number_text(e.east_mps)},
                                            {"north_mps", number_text(e.north_mps)},
                                            {"cov_ee", number_text(e.covariance[0])},
                                            {"cov_en", number_text(e.covariance[1])},
                                            {"cov_nn", number_text(e.covariance[2])},
                                            {"speed_scale", number_text(e.speed_scale)},
                                            {"residual_rms_mps", number_text(e.residual_rms_mps)},
                                            {"evidence", std::to_string(e.legs)}};
  // The vehicle's motion judged in this current, when it was (files of older stations lack it).
  if (const auto& r = c.speed_reference) {
    out["speed_reference_legs"] = std::to_string(r->legs);
    out["rms_over_ground_mps"] = number_text(r->rms_over_ground_mps);
    out["rms_through_water_mps"] = number_text(r->rms_through_water_mps);
    out["speed_reference_separation_mps"] = number_text(r->separation_mps);
    out["speed_reference"] = r->identified ? kin::to_string(*r->identified) : "";
  }
  if (const auto& d = c.drift_scatter) {
    out["drift_legs"] = std::to_string(d->legs);
    out["drift_along_mps"] = number_text(d->along_mps);
    out["drift_cross_mps"] = number_text(d->cross_mps);
    out["drift_mean_leg_s"] = number_text(d->mean_leg_s);
  }
  return out;
}

// The turn as stored: the row's columns, the raw turn and its normalised form.
std::string turn_record_message(const store::StoredTurn& t) {
  const store::TurnRow& r = t.row;
  json row = {{"cell_speed_mps", r.cell_speed_mps},
              {"cell_dheading_deg", r.cell_dheading_deg},
              {"commanded_speed_mps", r.commanded_speed_mps},
              {"goal_dheading_deg", r.goal_dheading_deg},
              {"observed_dheading_deg", r.observed_dheading_deg},
              {"start_time_s", r.start_time_s},
              {"end_time_s", r.end_time_s},
              {"advance_m", optional_json(r.advance_m)},
              {"transfer_m", optional_json(r.transfer_m)},
              {"condition_set_time_s", optional_json(r.condition_set_time_s)},
              {"start_heading_error_deg", optional_json(r.start_heading_error_deg)},
              {"start_yaw_rate_dps", optional_json(r.start_yaw_rate_dps)},
              {"source", kin::to_string(r.source)},
              {"quality", optional_json(r.quality)},
              {"speed_after_mps", optional_json(r.speed_after_mps)}};
  return json({{"id", r.id},
               {"status", kin::to_string(r.status)},
               {"reason", r.reason},
               {"row", std::move(row)},
               {"raw", kin::to_json(t.raw)},
               {"normalized", t.normalized ? kin::to_json(*t.normalized) : json()}})
      .dump();
}

std::string turn_scene(Context& ctx, const store::StoredTurn& t) {
  const store::TurnRow& r = t.row;
  fg::TurnScene s;
  s.t_s = r.start_time_s;
  const auto& samples = t.raw.samples();
  const double heading = t.raw.meta().initial_heading_deg;
  s.start = samples.empty() ? kin::Pose{0.0, 0.0, heading}
                            : kin::Pose{samples.front().x_m, samples.front().y_m, heading};
  s.speed_mps = r.commanded_speed_mps;
  s.dheading_deg = r.goal_dheading_deg;
  s.goal_heading_deg = kin::wrap360_deg(heading + r.goal_dheading_deg);
  // As the live connection names a turn that ended.
  s.state = r.status == kin::TurnStatus::ok ? "finished" : kin::to_string(r.status);
  if (!samples.empty()) {
    auto p = fg::scene_predictions(ctx, r.vehicle_id, r.commanded_speed_mps, r.goal_dheading_deg,
                                   s.start);
    s.predictions = std::move(p.predictions);
    s.cell_label = std::move(p.cell_label);
  }
  s.measured = t.raw.points();
  return fg::turn_scene_message(s);
}

// One message to write besides the navigation's: its time and where its content comes from.
struct Item {
  std::uint64_t log_time_ns = 0;
  fg::ChannelKind kind = fg::ChannelKind::turn;
  std::size_t index = 0;  // into the turns or the events
};

// The turns' and events' messages in log-time order: each stream is in time order only mostly
// (an event logged late, a harvested turn stored after later ones), so they are put in order
// together; ties keep stream order (turns before events). Navigation, read in time order from
// the store, is merged in as it is written (write_in_order).
std::vector<Item> other_messages(const MissionData& d) {
  std::vector<Item> items;
  items.reserve(2 * d.turns.size() + d.events.size());
  for (std::size_t i = 0; i < d.turns.size(); ++i) {
    items.push_back({fg::to_ns(d.turns[i].start_time_s), fg::ChannelKind::turn, i});
    items.push_back({fg::to_ns(d.turns[i].end_time_s), fg::ChannelKind::turn_record, i});
  }
  for (std::size_t i = 0; i < d.events.size(); ++i)
    items.push_back({fg::to_ns(d.events[i].t_s), fg::ChannelKind::log, i});
  std::stable_sort(items.begin(), items.end(),
                   [](const Item& a, const Item& b) { return a.log_time_ns < b.log_time_ns; });
  return items;
}

// Each stored sample as the navigation channels tell it (pose, tf, location, navigation draw on
// the same state), the geodetic position only with a datum. Throws std::out_of_range for a
// position too far from the datum.
fg::NavigationState navigation_state(const store::NavRow& r, const store::NavRow* previous,
                                     std::int64_t mission_id,
                                     const std::optional<vehicle::LocalGrid>& grid) {
  fg::NavigationState s;
  s.t_s = r.t_s;
  s.x_m = r.x_m;
  s.y_m = r.y_m;
  s.heading_deg = r.heading_deg;
  s.speed_mps = r.speed_mps;
  s.yaw_rate_dps = yaw_rate_dps(previous, r);
  s.desired_heading_deg = r.desired_heading_deg;
  s.desired_speed_mps = r.desired_speed_mps;
  s.helm_mode = r.helm_mode;
  s.mission_id = mission_id;
  if (grid) {
    const auto p = grid->to_geodetic(r.x_m, r.y_m);
    s.position = vehicle::LatLon{p.lat_deg, p.lon_deg};
  }
  return s;
}

// The mission's operating region, when its document parses as a mission (an imported log's does
// not).
std::optional<mission::OperatingRegion> mission_region(const MissionData& d) {
  try {
    const double max_speed = d.vehicle.max_speed_mps > 0.0 ? d.vehicle.max_speed_mps : 1e3;
    return mission::parse_mission_config(d.mission.config_json, max_speed).region;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The turn whose messages are being written, read from the store at its first message (the
// scene, at its start) and kept until its last (the record, at its end): turns seldom overlap,
// so only a few are held at once.
class TurnsInFlight {
 public:
  TurnsInFlight(store::Store& db, const MissionData& d) : db_(db), d_(d) {}
  const store::StoredTurn& at_start(std::size_t i) { return get(i); }
  store::StoredTurn at_end(std::size_t i) {
    get(i);
    auto node = held_.extract(i);
    return std::move(node.mapped());
  }

 private:
  const store::StoredTurn& get(std::size_t i) {
    auto it = held_.find(i);
    if (it != held_.end()) return it->second;
    auto turn = db_.turns().get(d_.turns[i].id);
    if (!turn) throw std::runtime_error("turn " + std::to_string(d_.turns[i].id) + " was deleted");
    return held_.emplace(i, std::move(*turn)).first->second;
  }
  store::Store& db_;
  const MissionData& d_;
  std::map<std::size_t, store::StoredTurn> held_;
};

std::string message_data(Context& ctx, const MissionData& d, const Item& item,
                         TurnsInFlight& turns) {
  const std::string& vid = d.mission.vehicle_id;
  switch (item.kind) {
    case fg::ChannelKind::turn:
      return turn_scene(ctx, turns.at_start(item.index));
    case fg::ChannelKind::turn_record:
      return turn_record_message(turns.at_end(item.index));
    case fg::ChannelKind::log: {
      const store::MissionEvent& e = d.events[item.index];
      const auto kind = mission::event_kind_from_string(e.kind);
      const bool warning = kind && mission::severity(*kind) == mission::Severity::warning;
      return fg::event_log_message(e.t_s, warning ? fg::LogLevel::warning : fg::LogLevel::info, vid,
                                   e.kind, e.message);
    }
    default:
      return {};
  }
}

std::string library_name() {
  const std::string version = AVK_STATION_VERSION;
  return version.empty() ? "avk-station" : "avk-station " + version;
}
}  // namespace

std::uint64_t McapChannelCounts::total() const {
  std::uint64_t n = 0;
  for (const auto& [topic, count] : per_topic)
    n += count;
  return n;
}

std::uint64_t McapChannelCounts::of(const std::string& topic) const {
  for (const auto& [t, count] : per_topic)
    if (t == topic) return count;
  return 0;
}

Result<McapExport> export_mission_mcap(Context& ctx, std::int64_t mission_id,
                                       const McapExportOptions& options,
                                       const mcap::Writer::Sink& sink) {
  store::Store& db = store_of(ctx);
  const auto mission = db.missions().get(mission_id);
  if (!mission) return not_found("no mission " + std::to_string(mission_id));
  std::optional<vehicle::LocalGrid> grid;
  if (options.datum) {
    try {
      grid.emplace(options.datum->lat_deg, options.datum->lon_deg);
    } catch (const std::invalid_argument& e) {
      return invalid_argument("datum", e.what());
    }
  }
  MissionData d = load_mission(db, *mission);
  const auto region = mission_region(d);

  mcap::WriterOptions wo;
  wo.compression = options.compression;
  wo.library = library_name();
  mcap::Writer w(wo, sink);
  const std::string& vid = mission->vehicle_id;
  std::map<std::string, std::uint16_t> schema_ids;
  std::map<fg::ChannelKind, std::uint16_t> channel_ids;
  McapExport out;
  out.mission_id = mission_id;
  out.vehicle_id = vid;
  for (const auto kind :
       {fg::ChannelKind::pose, fg::ChannelKind::transform, fg::ChannelKind::location,
        fg::ChannelKind::navigation, fg::ChannelKind::turn, fg::ChannelKind::region,
        fg::ChannelKind::log, fg::ChannelKind::turn_record}) {
    if (kind == fg::ChannelKind::location && !grid) continue;
    if (kind == fg::ChannelKind::region && !region) continue;
    const fg::ChannelSpec spec = fg::channel_spec(vid, kind);
    auto schema = schema_ids.find(spec.schema_name);
    if (schema == schema_ids.end())
      schema = schema_ids
                   .emplace(spec.schema_name,
                            w.add_schema(spec.schema_name, fg::kSchemaEncoding, spec.schema))
                   .first;
    channel_ids[kind] = w.add_channel(schema->second, spec.topic, fg::kMessageEncoding);
    out.messages.per_topic.emplace_back(spec.topic, 0);
  }
  // A datum too far from the track is the request's mistake: said before anything is written.
  if (grid) {
    std::optional<std::string> too_far;
    db.navigation().for_each(mission_id, [&](const store::NavRow& r) {
      if (too_far) return;
      try {
        (void)grid->to_geodetic(r.x_m, r.y_m);
      } catch (const std::out_of_range& e) {
        too_far = e.what();
      }
    });
    if (too_far)
      return invalid_argument("datum", "the track is too far from the datum: " + *too_far);
  }
  std::map<fg::ChannelKind, std::uint64_t> counts;
  const auto add = [&](fg::ChannelKind kind, std::uint64_t t_ns, const std::string& data) {
    const auto channel = channel_ids.find(kind);
    if (channel == channel_ids.end()) return;
    w.add_message(channel->second, t_ns, t_ns, data);
    ++counts[kind];
  };
  // The messages in log-time order, ties in stream order: the region first (at the first
  // sample's time), then navigation, turns, events.
  const std::vector<Item> others = other_messages(d);
  std::size_t next_other = 0;
  TurnsInFlight turns(db, d);
  const auto others_before = [&](std::uint64_t t_ns) {
    for (; next_other < others.size() && others[next_other].log_time_ns < t_ns; ++next_other) {
      const Item& item = others[next_other];
      if (channel_ids.contains(item.kind))
        add(item.kind, item.log_time_ns, message_data(ctx, d, item, turns));
    }
  };
  bool region_written = false;
  const auto write_region = [&](double t_s) {
    const std::uint64_t t_ns = fg::to_ns(t_s);
    others_before(t_ns);
    if (region) add(fg::ChannelKind::region, t_ns, fg::region_scene_message(t_s, *region));
    region_written = true;
  };
  std::optional<store::NavRow> previous;
  db.navigation().for_each(mission_id, [&](const store::NavRow& r) {
    if (!region_written) write_region(r.t_s);
    const std::uint64_t t_ns = fg::to_ns(r.t_s);
    others_before(t_ns);
    const fg::NavigationState nav =
        navigation_state(r, previous ? &*previous : nullptr, mission_id, grid);
    add(fg::ChannelKind::pose, t_ns, fg::pose_message(nav));
    add(fg::ChannelKind::transform, t_ns, fg::transform_message(nav, vid));
    if (grid) add(fg::ChannelKind::location, t_ns, fg::location_message(nav, vid));
    add(fg::ChannelKind::navigation, t_ns, fg::navigation_message(nav));
    previous = r;
    ++d.nav_samples;
  });
  if (!region_written) write_region(mission->started_s.value_or(0.0));
  for (; next_other < others.size(); ++next_other) {
    const Item& item = others[next_other];
    if (channel_ids.contains(item.kind))
      add(item.kind, item.log_time_ns, message_data(ctx, d, item, turns));
  }
  for (auto& [topic, n] : out.messages.per_topic)
    for (const auto& [kind, count] : counts)
      if (fg::topic(vid, kind) == topic) n = count;
  w.add_metadata(kMissionRecord, mission_entries(d));
  w.add_metadata(kVehicleRecord, vehicle_entries(d.vehicle));
  w.add_metadata(kConditionSetsRecord, condition_set_entries(d.condition_sets));
  if (d.current) w.add_metadata(kCurrentRecord, current_entries(*d.current));
  out.bytes = w.finish();
  return out;
}

}  // namespace avk::app
