#include "kinematics/turn_json.hpp"

#include <array>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kinematics/json_parse.hpp"
#include "kinematics/turn_keys.hpp"
#include "kinematics/turn_text.hpp"

namespace avk::kinematics {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "avk-turn";
constexpr int kVersion = 1;
constexpr std::size_t kSampleArity = kTurnSampleArity;

// Every key a document must have: what it is, the turn's own (kinematics/turn_keys.hpp) in their
// order, and how its samples are laid out.
constexpr auto kKeys = [] {
  std::array<const char*, 10 + kTurnMetaDoubles.size()> keys{};
  std::size_t n = 0;
  for (const char* k : {"format", "version", kTurnVehicleIdKey, kTurnMissionIdKey, kTurnStatusKey,
                        kTurnStatusReasonKey, kTurnNormalizedKey})
    keys[n++] = k;
  for (const auto& d : kTurnMetaDoubles)
    keys[n++] = d.name;
  for (const char* k : {kTurnWarningsKey, "sample_fields", kTurnSamplesKey})
    keys[n++] = k;
  return keys;
}();

// Keys a document may leave out: an absent key is the field's default (no removed current: over
// ground; source collection; no quality), so documents written before the field existed load.
constexpr std::array<const char*, 4> kOptionalKeys = {
    "removed_current_east_mps",
    "removed_current_north_mps",
    "source",
    "quality",
};
constexpr const char* kSpeedAfterKey = kTurnOptionalMetaDoubles[1].name;

// A turn document is an object of arrays of arrays; anything deeper is not a turn, and refusing
// it while parsing keeps a hostile "[[[[..." from building a huge tree first.
constexpr JsonLimits kTurnLimits{
    .max_depth = 3,
    .max_values = kMaxTurnRecordSamples * (kSampleArity + 1) + kMaxTurnRecordWarnings + 1024,
    .max_array_elements = kMaxTurnRecordSamples,
    .max_object_keys = 64};

std::string sample_pointer(std::size_t i) {
  std::string out = "/samples/";
  out += std::to_string(i);
  return out;
}

// The sample a parse problem lies in ("/samples/12/3" -> 12), the position turn errors report.
std::size_t sample_index_of(const std::string& pointer) {
  constexpr std::string_view prefix = "/samples/";
  if (!pointer.starts_with(prefix)) return 0;
  std::size_t i = 0;
  for (std::size_t k = prefix.size(); k < pointer.size() && pointer[k] >= '0' && pointer[k] <= '9';
       ++k)
    i = i * 10 + static_cast<std::size_t>(pointer[k] - '0');
  return i;
}

const json& member(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) throw ParseError(json_member_pointer(key), 0, "missing key");
  return *it;
}

std::string read_string(const json& j, const char* key) {
  const json& v = member(j, key);
  if (!v.is_string()) throw ParseError(json_member_pointer(key), 0, "expected a string");
  const auto& s = v.get_ref<const std::string&>();
  if (!is_valid_utf8(s)) throw ParseError(json_member_pointer(key), 0, "string is not valid UTF-8");
  return s;
}

// A json built in memory (not parsed) may hold NaN or infinity, so check finiteness here too.
double read_double(const json& v, const std::string& pointer, std::size_t position) {
  if (!v.is_number()) throw ParseError(pointer, position, "expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw ParseError(pointer, position, "NaN and infinity are not allowed");
  return d;
}

}  // namespace

json to_json(const TurnSequence& turn) {
  check_turn_serialisable(turn);
  const TurnMeta& m = turn.meta();
  json j = json::object();
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["vehicle_id"] = m.vehicle_id;
  j["mission_id"] = m.mission_id;
  j["status"] = to_string(m.status);
  j["status_reason"] = m.status_reason;
  j["normalized"] = m.normalized;
  for (const auto& [name, ptr] : kTurnMetaDoubles)
    j[name] = m.*ptr;
  if (m.removed_current) {
    j["removed_current_east_mps"] = m.removed_current->east_mps;
    j["removed_current_north_mps"] = m.removed_current->north_mps;
  }
  if (m.source != TurnSource::collection) j["source"] = to_string(m.source);
  if (m.quality) j["quality"] = *m.quality;
  for (const auto& [name, ptr] : kTurnOptionalMetaDoubles)
    if (m.*ptr) j[name] = *(m.*ptr);
  j["warnings"] = turn.warnings();
  json fields = json::array();
  for (const char* f : kTurnSampleFields)
    fields.push_back(f);
  j["sample_fields"] = std::move(fields);
  json samples = json::array();
  samples.get_ref<json::array_t&>().reserve(turn.samples().size());
  for (const auto& s : turn.samples()) {
    samples.push_back(json::array({s.t_s, s.x_m, s.y_m, s.heading_deg, s.speed_mps}));
  }
  j["samples"] = std::move(samples);
  return j;
}

TurnSequence turn_from_json(const json& j) {
  if (!j.is_object()) throw ParseError("", 0, "a turn must be a JSON object");
  // Format and version first: a document of another kind should say so rather than list its
  // keys as unknown.
  const json& format = member(j, "format");
  if (!format.is_string() || format.get_ref<const std::string&>() != kFormat) {
    throw ParseError("/format", 0, std::string("format must be \"") + kFormat + "\"");
  }
  const json& version = member(j, "version");
  if (!version.is_number_integer() || version != kVersion) {
    throw ParseError("/version", 0,
                     "unsupported version; this reader knows " + std::to_string(kVersion));
  }
  for (const auto& item : j.items()) {
    bool known = false;
    for (const char* k : kKeys)
      known = known || item.key() == k;
    for (const char* k : kOptionalKeys)
      known = known || item.key() == k;
    for (const auto& [k, ptr] : kTurnOptionalMetaDoubles)
      known = known || item.key() == k;
    if (!known) throw ParseError(json_member_pointer(item.key()), 0, "unknown key");
  }
  for (const char* k : kKeys)
    member(j, k);

  TurnMeta m;
  m.vehicle_id = read_string(j, "vehicle_id");
  m.mission_id = read_string(j, "mission_id");
  const auto status = turn_status_from_string(read_string(j, "status"));
  if (!status) throw ParseError("/status", 0, "status must be ok|aborted|rejected");
  m.status = *status;
  m.status_reason = read_string(j, "status_reason");
  const json& normalized = member(j, "normalized");
  if (!normalized.is_boolean()) throw ParseError("/normalized", 0, "expected true or false");
  m.normalized = normalized.get<bool>();
  for (const auto& [name, ptr] : kTurnMetaDoubles)
    m.*ptr = read_double(member(j, name), json_member_pointer(name), 0);
  const bool has_east = j.contains("removed_current_east_mps");
  if (has_east != j.contains("removed_current_north_mps")) {
    throw ParseError(has_east ? "/removed_current_north_mps" : "/removed_current_east_mps", 0,
                     "the removed current needs both its east and north components");
  }
  if (has_east) {
    m.removed_current = WaterCurrent{
        read_double(j.at("removed_current_east_mps"), "/removed_current_east_mps", 0),
        read_double(j.at("removed_current_north_mps"), "/removed_current_north_mps", 0)};
  }
  if (const auto it = j.find("source"); it != j.end()) {
    const auto source =
        it->is_string() ? turn_source_from_string(it->get<std::string>()) : std::nullopt;
    if (!source) throw ParseError("/source", 0, "source must be collection|harvested");
    m.source = *source;
  }
  if (const auto it = j.find("quality"); it != j.end()) {
    m.quality = read_double(*it, "/quality", 0);
    if (*m.quality < 0.0 || *m.quality > 1.0)
      throw ParseError("/quality", 0, "quality must be within 0..1");
  }
  for (const auto& [name, ptr] : kTurnOptionalMetaDoubles) {
    if (const auto it = j.find(name); it != j.end())
      m.*ptr = read_double(*it, json_member_pointer(name), 0);
  }
  if (m.speed_after_mps && !(*m.speed_after_mps > 0.0))
    throw ParseError(json_member_pointer(kSpeedAfterKey), 0, "must be > 0");

  const json& warnings = member(j, "warnings");
  if (!warnings.is_array()) throw ParseError("/warnings", 0, "expected an array of strings");
  if (warnings.size() > kMaxTurnRecordWarnings) {
    throw ParseError("/warnings", 0,
                     "more than " + std::to_string(kMaxTurnRecordWarnings) + " warnings");
  }
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const json& w = warnings[i];
    if (!w.is_string() || !is_valid_utf8(w.get_ref<const std::string&>())) {
      throw ParseError("/warnings/" + std::to_string(i), 0, "expected a UTF-8 string");
    }
  }

  // The fields are fixed; the array is there so a reader of the file need not guess the order.
  json expected_fields = json::array();
  for (const char* f : kTurnSampleFields)
    expected_fields.push_back(f);
  if (member(j, "sample_fields") != expected_fields) {
    throw ParseError("/sample_fields", 0, "sample_fields must be " + expected_fields.dump());
  }

  const json& samples = member(j, "samples");
  if (!samples.is_array()) throw ParseError("/samples", 0, "expected an array of samples");
  if (samples.size() > kMaxTurnRecordSamples) {
    throw ParseError("/samples", 0,
                     "more than " + std::to_string(kMaxTurnRecordSamples) + " samples");
  }
  std::vector<TurnSample> out;
  out.reserve(samples.size());  // the array exists already, so its size is not just a claim
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const json& s = samples[i];
    if (!s.is_array() || s.size() != kSampleArity) {
      throw ParseError(sample_pointer(i), i,
                       "a sample is an array of 5 numbers [t_s,x_m,y_m,heading_deg,speed_mps]");
    }
    const auto value = [&](std::size_t c) {
      std::string pointer = sample_pointer(i);
      pointer += '/';
      pointer += std::to_string(c);
      return read_double(s[c], pointer, i);
    };
    out.push_back({value(0), value(1), value(2), value(3), value(4)});
  }

  TurnSequence turn(std::move(m), std::move(out));
  for (const json& w : warnings)
    turn.add_warning(w.get<std::string>());
  return turn;
}

std::string to_json_string(const TurnSequence& turn) {
  std::string out = to_json(turn).dump();
  if (out.size() > kMaxTurnRecordBytes) {
    throw std::invalid_argument("turn cannot be serialised: the JSON would exceed " +
                                std::to_string(kMaxTurnRecordBytes) + " bytes");
  }
  return out;
}

TurnSequence parse_turn_json(std::string_view text) {
  if (text.size() > kMaxTurnRecordBytes) {
    throw ParseError("json", kMaxTurnRecordBytes,
                     "document is longer than " + std::to_string(kMaxTurnRecordBytes) + " bytes");
  }
  json root;
  try {
    root = parse_json_bounded(text, kTurnLimits);
  } catch (const JsonSyntaxError& e) {
    throw ParseError("json", e.position(), "not valid JSON: " + e.reason());
  } catch (const ParseError& e) {
    // Past a limit or a duplicate key: reported at the sample it lies in, as every turn error.
    throw ParseError(e.field(), sample_index_of(e.field()), e.message());
  }
  return turn_from_json(root);
}

}  // namespace avk::kinematics
