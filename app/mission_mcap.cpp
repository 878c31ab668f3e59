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

constexpr const char* kMissionRecord = "avk.mission";
constexpr const char* kVehicleRecord = "avk.vehicle";
constexpr const char* kConditionSetsRecord = "avk.condition_sets";
constexpr const char* kCurrentRecord = "avk.current";

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
  d.vehicle = db.get_vehicle(m.vehicle_id)
                  .value_or(vehicle::VehicleInfo{m.vehicle_id, "", 0.0, std::nullopt});
  constexpr int kPage = 1000;
  for (std::int64_t after = 0;;) {
    auto page = db.list_events(m.id, after, kPage);
    if (page.empty()) break;
    after = page.back().id;
    d.events.insert(d.events.end(), page.begin(), page.end());
  }
  for_each_mission_turn(db, m.id, std::nullopt,
                        [&](const store::TurnRow& t) { d.turns.push_back(t); });
  d.condition_sets = db.condition_sets(m.id);
  d.current = db.mission_current(m.id);
  return d;
}

// Numbers in metadata records are JSON number text: shortest round-trip, so an import reads the
// same double back. An absent value is the empty string.
std::string number_text(double v) {
  return json(v).dump();
}
std::string number_text(const std::optional<double>& v) {
  return v ? number_text(*v) : std::string();
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

// Heading change over time from the previous sample, wrapped, + clockwise.
std::optional<double> yaw_rate_dps(const store::NavRow* previous, const store::NavRow& r) {
  if (!previous || !(r.t_s > previous->t_s)) return std::nullopt;
  return kin::angle180_deg(r.heading_deg - previous->heading_deg) / (r.t_s - previous->t_s);
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
    auto turn = db_.get_turn(d_.turns[i].id);
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

// ---------------------------------------------------------------------------------------------
// Import

// What is wrong with the file; becomes invalid_argument naming "file".
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const std::map<std::string, std::string>* find_record(const mcap::McapContents& c,
                                                      const std::string& name) {
  for (const auto& m : c.metadata)
    if (m.name == name) return &m.entries;
  return nullptr;
}

const std::map<std::string, std::string>& require_record(const mcap::McapContents& c,
                                                         const std::string& name) {
  const auto* r = find_record(c, name);
  if (!r) throw FileError("the file has no " + name + " metadata record");
  return *r;
}

const std::string& entry(const std::map<std::string, std::string>& r, const std::string& record,
                         const std::string& key) {
  const auto it = r.find(key);
  if (it == r.end()) throw FileError(record + " metadata has no '" + key + "'");
  return it->second;
}

// `v` when `range` holds it; else what is wrong, naming it as `what`.
double in_range(double v, const vehicle::ValueRange& range, const std::string& what) {
  if (!range.contains(v))
    throw FileError(what + " " + number_text(v) + " is out of range " + vehicle::to_string(range));
  return v;
}

std::optional<double> optional_number_entry(const std::map<std::string, std::string>& r,
                                            const std::string& record, const std::string& key) {
  const std::string& text = entry(r, record, key);
  if (text.empty()) return std::nullopt;
  const json j = json::parse(text, nullptr, false);
  if (!j.is_number())
    throw FileError(record + " metadata '" + key + "' is not a number: '" + text + "'");
  return j.get<double>();
}

double number_entry(const std::map<std::string, std::string>& r, const std::string& record,
                    const std::string& key) {
  const auto v = optional_number_entry(r, record, key);
  if (!v) throw FileError(record + " metadata '" + key + "' is empty");
  return *v;
}

// A time on the station clock, in its range (vehicle/nav_ranges.hpp).
std::optional<double> optional_clock_entry(const std::map<std::string, std::string>& r,
                                           const std::string& record, const std::string& key) {
  const auto v = optional_number_entry(r, record, key);
  if (v) in_range(*v, vehicle::kClockRange_s, record + " metadata '" + key + "'");
  return v;
}

std::int64_t integer_entry(const std::map<std::string, std::string>& r, const std::string& record,
                           const std::string& key) {
  const std::string& text = entry(r, record, key);
  const json j = json::parse(text, nullptr, false);
  if (!j.is_number_integer())
    throw FileError(record + " metadata '" + key + "' is not an integer: '" + text + "'");
  return j.get<std::int64_t>();
}

// Where a message came from, for errors: "message 12 on /usim/navigation".
std::string where(const mcap::MessageRecord& m, const std::string& topic) {
  return "message " + std::to_string(m.sequence) + " on " + topic;
}

// Member access of a message that names the message and the member when it does not fit.
class MessageFields {
 public:
  MessageFields(const json& j, std::string where) : j_(j), where_(std::move(where)) {}

  const json& member(const char* key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) throw FileError(where_ + ": no '" + key + "'");
    return *it;
  }
  double number(const char* key) const {
    const json& v = member(key);
    if (!v.is_number()) throw FileError(where_ + ": '" + key + "' is not a number");
    return v.get<double>();
  }
  std::optional<double> optional_number(const char* key) const {
    const json& v = member(key);
    if (v.is_null()) return std::nullopt;
    return number(key);
  }
  // A number in the range every reader of navigation holds (vehicle/nav_ranges.hpp).
  double number(const char* key, const vehicle::ValueRange& range) const {
    return in_range(number(key), range, where_ + ": '" + key + "'");
  }
  std::optional<double> optional_number(const char* key, const vehicle::ValueRange& range) const {
    const auto v = optional_number(key);
    if (v) in_range(*v, range, where_ + ": '" + key + "'");
    return v;
  }
  std::string text(const char* key) const {
    const json& v = member(key);
    if (!v.is_string()) throw FileError(where_ + ": '" + key + "' is not a string");
    return v.get<std::string>();
  }
  std::int64_t integer(const char* key) const {
    const json& v = member(key);
    if (!v.is_number_integer()) throw FileError(where_ + ": '" + key + "' is not an integer");
    return v.get<std::int64_t>();
  }
  const std::string& where() const { return where_; }

 private:
  const json& j_;
  std::string where_;
};

// `previous`: the navigation sample before it in the file, which it must not precede (the
// station writes them in time order).
store::NavRow nav_row(const MessageFields& f, const store::NavRow* previous) {
  store::NavRow r;
  r.t_s = f.number("t_s", vehicle::kClockRange_s);
  if (previous && r.t_s < previous->t_s)
    throw FileError(f.where() + ": 't_s' " + number_text(r.t_s) +
                    " is earlier than the navigation sample before it (" +
                    number_text(previous->t_s) + ")");
  r.x_m = f.number("x_m", vehicle::kGridRange_m);
  r.y_m = f.number("y_m", vehicle::kGridRange_m);
  r.heading_deg = f.number("heading_deg", vehicle::kHeadingRange_deg);
  r.speed_mps = f.number("speed_mps", vehicle::kSpeedRange_mps);
  r.desired_heading_deg = f.optional_number("desired_heading_deg", vehicle::kHeadingRange_deg);
  r.desired_speed_mps = f.optional_number("desired_speed_mps", vehicle::kSpeedRange_mps);
  r.helm_mode = f.member("helm_mode").is_null() ? std::string() : f.text("helm_mode");
  return r;
}

store::MissionEvent event_row(const MessageFields& f) {
  store::MissionEvent e;
  e.t_s = f.number("t_s", vehicle::kClockRange_s);
  e.kind = f.text("kind");
  e.message = f.text("message");
  return e;
}

kin::TurnSequence turn_document(const MessageFields& f, const char* key) {
  try {
    return kin::turn_from_json(f.member(key));
  } catch (const kin::ParseError& e) {
    throw FileError(f.where() + ": '" + key + "' is not a turn record: " + e.what());
  } catch (const std::exception& e) {
    throw FileError(f.where() + ": '" + key + "' is not a turn record: " + e.what());
  }
}

store::StoredTurn stored_turn(const MessageFields& f, const std::string& vehicle_id) {
  store::StoredTurn t;
  store::TurnRow& r = t.row;
  r.id = f.integer("id");
  r.vehicle_id = vehicle_id;
  const auto status = kin::turn_status_from_string(f.text("status"));
  if (!status) throw FileError(f.where() + ": unknown turn status '" + f.text("status") + "'");
  r.status = *status;
  r.reason = f.text("reason");
  const json& row_json = f.member("row");
  if (!row_json.is_object()) throw FileError(f.where() + ": 'row' is not an object");
  const MessageFields row(row_json, f.where() + ", row");
  r.cell_speed_mps = row.number("cell_speed_mps", vehicle::kSpeedRange_mps);
  r.cell_dheading_deg = row.number("cell_dheading_deg");
  r.commanded_speed_mps = row.number("commanded_speed_mps", vehicle::kSpeedRange_mps);
  r.goal_dheading_deg = row.number("goal_dheading_deg");
  r.observed_dheading_deg = row.number("observed_dheading_deg");
  r.start_time_s = row.number("start_time_s", vehicle::kClockRange_s);
  r.end_time_s = row.number("end_time_s", vehicle::kClockRange_s);
  if (r.end_time_s < r.start_time_s)
    throw FileError(row.where() + ": 'end_time_s' " + number_text(r.end_time_s) +
                    " is before 'start_time_s' " + number_text(r.start_time_s));
  r.advance_m = row.optional_number("advance_m");
  r.transfer_m = row.optional_number("transfer_m");
  r.condition_set_time_s = row.optional_number("condition_set_time_s");
  r.start_heading_error_deg = row.optional_number("start_heading_error_deg");
  r.start_yaw_rate_dps = row.optional_number("start_yaw_rate_dps");
  const auto source = kin::turn_source_from_string(row.text("source"));
  if (!source) throw FileError(f.where() + ": unknown turn source '" + row.text("source") + "'");
  r.source = *source;
  r.quality = row.optional_number("quality");
  r.speed_after_mps = row.optional_number("speed_after_mps");
  t.raw = turn_document(f, "raw");
  if (!f.member("normalized").is_null()) t.normalized = turn_document(f, "normalized");
  return t;
}

store::Mission mission_row(const std::map<std::string, std::string>& r) {
  const std::string rec = kMissionRecord;
  store::Mission m;
  m.id = integer_entry(r, rec, "id");
  m.vehicle_id = entry(r, rec, "vehicle_id");
  m.name = entry(r, rec, "name");
  m.config_json = entry(r, rec, "config_json");
  const std::string& status = entry(r, rec, "status");
  const auto parsed = store::mission_status_from_string(status);
  if (!parsed) throw FileError(rec + " metadata 'status' is unknown: '" + status + "'");
  m.status = *parsed;
  m.status_reason = entry(r, rec, "status_reason");
  m.created_utc = entry(r, rec, "created_utc");
  m.started_s = optional_clock_entry(r, rec, "started_s");
  m.ended_s = optional_clock_entry(r, rec, "ended_s");
  // A mission exported while it ran is not running here: no process of this station runs it.
  if (m.status == store::MissionStatus::running || m.status == store::MissionStatus::paused) {
    m.status = store::MissionStatus::interrupted;
    m.status_reason = "imported from a recording made while it ran";
  }
  return m;
}

vehicle::VehicleInfo vehicle_row(const std::map<std::string, std::string>& r) {
  const std::string rec = kVehicleRecord;
  return {entry(r, rec, "id"), entry(r, rec, "kind"), number_entry(r, rec, "max_speed_mps"),
          optional_number_entry(r, rec, "length_m")};
}

std::vector<store::ConditionSetTiming> condition_sets(const std::map<std::string, std::string>& r) {
  const json a = json::parse(entry(r, kConditionSetsRecord, "json"), nullptr, false);
  if (!a.is_array()) throw FileError(std::string(kConditionSetsRecord) + " is not a JSON array");
  std::vector<store::ConditionSetTiming> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_object())
      throw FileError(std::string(kConditionSetsRecord) + " [" + std::to_string(i) +
                      "] is not an object");
    const MessageFields f(a[i], std::string(kConditionSetsRecord) + " [" + std::to_string(i) + "]");
    out.push_back({f.number("start_s", vehicle::kClockRange_s),
                   f.number("end_s", vehicle::kClockRange_s),
                   f.number("target_speed_mps", vehicle::kSpeedRange_mps), f.text("outcome")});
  }
  return out;
}

store::StoredCurrent current_row(const std::map<std::string, std::string>& r) {
  const std::string rec = kCurrentRecord;
  store::StoredCurrent c;
  c.t_s = in_range(number_entry(r, rec, "t_s"), vehicle::kClockRange_s, rec + " metadata 't_s'");
  c.method = entry(r, rec, "method");
  c.estimate.east_mps = number_entry(r, rec, "east_mps");
  c.estimate.north_mps = number_entry(r, rec, "north_mps");
  c.estimate.covariance = {number_entry(r, rec, "cov_ee"), number_entry(r, rec, "cov_en"),
                           number_entry(r, rec, "cov_nn")};
  c.estimate.speed_scale = number_entry(r, rec, "speed_scale");
  c.estimate.residual_rms_mps = number_entry(r, rec, "residual_rms_mps");
  const std::int64_t evidence = integer_entry(r, rec, "evidence");
  if (evidence < 0) throw FileError(rec + " metadata 'evidence' is negative");
  c.estimate.legs = static_cast<std::size_t>(evidence);
  const auto count = [&](const char* key) {
    const std::int64_t n = integer_entry(r, rec, key);
    if (n < 0) throw FileError(rec + " metadata '" + key + "' is negative");
    return static_cast<std::size_t>(n);
  };
  if (r.count("speed_reference_legs")) {
    kin::SpeedReferenceEvidence e;
    e.legs = count("speed_reference_legs");
    e.rms_over_ground_mps = number_entry(r, rec, "rms_over_ground_mps");
    e.rms_through_water_mps = number_entry(r, rec, "rms_through_water_mps");
    e.separation_mps = number_entry(r, rec, "speed_reference_separation_mps");
    const std::string& name = entry(r, rec, "speed_reference");
    if (!name.empty()) {
      e.identified = kin::parse_speed_reference(name);
      if (!e.identified)
        throw FileError(rec + " metadata 'speed_reference' is not over_ground or through_water: '" +
                        name + "'");
    }
    c.speed_reference = e;
  }
  if (r.count("drift_legs"))
    c.drift_scatter = kin::DriftScatter{
        number_entry(r, rec, "drift_along_mps"), number_entry(r, rec, "drift_cross_mps"),
        count("drift_legs"), number_entry(r, rec, "drift_mean_leg_s")};
  return c;
}

void check_count(const std::map<std::string, std::string>& r, const char* key, std::size_t read,
                 const std::string& what) {
  const std::int64_t expected = integer_entry(r, kMissionRecord, key);
  if (expected != static_cast<std::int64_t>(read))
    throw FileError("the file holds " + std::to_string(read) + " " + what + " but " +
                    kMissionRecord + " says " + std::to_string(expected) +
                    " (a truncated or edited file?)");
}

// The file read and checked into what the store imports.
struct ReadMission {
  store::MissionImport data;
  std::int64_t source_id = 0;
  McapChannelCounts messages;
};

ReadMission read_mission(std::string_view bytes) {
  mcap::McapContents c;
  try {
    c = mcap::read_mcap(bytes);
  } catch (const mcap::McapError& e) {
    throw FileError(std::string("not a readable MCAP file: ") + e.what());
  }
  const auto* mission_record = find_record(c, kMissionRecord);
  if (!mission_record)
    throw FileError(
        "not a mission recording of AVK Station: the file has no avk.mission metadata record "
        "(only files written by `avk mission export` or the export route import)");
  const auto& mr = *mission_record;
  const auto version = mr.find("avk_mcap_version");
  if (version == mr.end()) throw FileError("avk.mission metadata has no 'avk_mcap_version'");
  if (version->second != kMissionMcapVersion)
    throw FileError("avk.mission metadata says avk_mcap_version '" + version->second +
                    "'; this station reads version " + kMissionMcapVersion);
  ReadMission out;
  store::MissionImport& d = out.data;
  d.mission = mission_row(mr);
  out.source_id = d.mission.id;
  d.vehicle = vehicle_row(require_record(c, kVehicleRecord));
  if (d.vehicle.id != d.mission.vehicle_id)
    throw FileError("avk.vehicle metadata is vehicle '" + d.vehicle.id +
                    "' but the mission's is '" + d.mission.vehicle_id + "'");
  d.condition_sets = condition_sets(require_record(c, kConditionSetsRecord));
  if (const auto* cur = find_record(c, kCurrentRecord)) d.current = current_row(*cur);

  std::map<std::uint16_t, std::pair<std::string, std::optional<fg::ChannelKind>>> channels;
  std::ranges::sort(c.channels, {},
                    &mcap::ChannelRecord::id);  // listed as the writer numbered them
  for (const auto& ch : c.channels) {
    channels[ch.id] = {ch.topic, fg::channel_kind_of(ch.topic, d.mission.vehicle_id)};
    out.messages.per_topic.emplace_back(ch.topic, 0);
  }
  std::vector<std::pair<std::int64_t, std::size_t>> turn_order;  // original id, index
  for (const auto& m : c.messages) {
    const auto ch = channels.find(m.channel_id);
    if (ch == channels.end())
      throw FileError("message " + std::to_string(m.sequence) + " is on channel " +
                      std::to_string(m.channel_id) + ", which the file does not define");
    const std::string& topic = ch->second.first;
    for (auto& [t, n] : out.messages.per_topic)
      if (t == topic) ++n;
    const json j = json::parse(m.data, nullptr, false);
    if (j.is_discarded() || !j.is_object())
      throw FileError(where(m, topic) + ": not a JSON object");
    const MessageFields f(j, where(m, topic));
    if (!ch->second.second) continue;
    switch (*ch->second.second) {
      case fg::ChannelKind::navigation:
        d.nav.push_back(nav_row(f, d.nav.empty() ? nullptr : &d.nav.back()));
        break;
      case fg::ChannelKind::log:
        d.events.push_back(event_row(f));
        break;
      case fg::ChannelKind::turn_record:
        d.turns.push_back(stored_turn(f, d.mission.vehicle_id));
        turn_order.emplace_back(d.turns.back().row.id, d.turns.size() - 1);
        break;
      default:
        break;  // drawn from the stored data; nothing of it is imported
    }
  }
  check_count(mr, "nav_samples", d.nav.size(), "navigation samples");
  check_count(mr, "events", d.events.size(), "events");
  check_count(mr, "turns", d.turns.size(), "turn records");
  // The file holds the turns at their end times; the station stored them by id, which a
  // harvested turn (stored after later turns) does not follow.
  std::stable_sort(turn_order.begin(), turn_order.end());
  std::vector<store::StoredTurn> by_id;
  by_id.reserve(d.turns.size());
  for (const auto& [id, index] : turn_order)
    by_id.push_back(std::move(d.turns[index]));
  d.turns = std::move(by_id);
  return out;
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
  store::Store& db = ctx.db();
  const auto mission = db.get_mission(mission_id);
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
    db.for_each_nav(mission_id, [&](const store::NavRow& r) {
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
  db.for_each_nav(mission_id, [&](const store::NavRow& r) {
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

Result<McapImport> import_mission_mcap(Context& ctx, std::string_view bytes) {
  ReadMission r;
  try {
    r = read_mission(bytes);
  } catch (const FileError& e) {
    return invalid_argument("file", e.what());
  }
  store::MissionImport& d = r.data;
  if (auto text = check_imported_text(d); !text) return text.error();
  if (d.current && current_is_significant(d.current->estimate)) {
    // The water-frame form is derived, as the station derives it when it stores the estimate.
    std::vector<std::pair<std::int64_t, kin::TurnSequence>> ok;
    for (std::size_t i = 0; i < d.turns.size(); ++i)
      if (d.turns[i].row.status == kin::TurnStatus::ok)
        ok.emplace_back(static_cast<std::int64_t>(i), d.turns[i].raw);
    for (auto& [index, turn] : water_frame_turns(ok, water_current(d.current->estimate)))
      d.water_turns.emplace_back(static_cast<std::size_t>(index), std::move(turn));
  }
  McapImport out;
  out.source_mission_id = r.source_id;
  out.vehicle_id = d.mission.vehicle_id;
  out.nav_samples = d.nav.size();
  out.events = d.events.size();
  out.turns = d.turns.size();
  out.condition_sets = d.condition_sets.size();
  out.current = d.current.has_value();
  out.messages = std::move(r.messages);
  store::Store& db = ctx.db();
  // The turn documents keep the mission id text they were recorded under: where they came from.
  out.mission_id = db.import_mission(d);
  return out;
}

}  // namespace avk::app
