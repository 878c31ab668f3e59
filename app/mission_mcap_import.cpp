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
#include "app/mission_mcap_format.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/turn_json.hpp"
#include "mission/event_kind.hpp"
#include "mission/mission_config.hpp"
#include "vehicle/nav_ranges.hpp"

namespace avk::app {

namespace {

using nlohmann::json;
namespace fg = foxglove;
namespace kin = kinematics;

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
  store::Store& db = store_of(ctx);
  // The turn documents keep the mission id text they were recorded under: where they came from.
  out.mission_id = db.import_mission(d);
  return out;
}

}  // namespace avk::app
