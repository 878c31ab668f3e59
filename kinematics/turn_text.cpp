#include "kinematics/turn_text.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "kinematics/turn_keys.hpp"

namespace avk::kinematics {

namespace {

constexpr std::string_view kMagic = "AVKTURN/";
constexpr unsigned kVersion = 1;
constexpr std::size_t kSampleArity = kTurnSampleArity;
constexpr const auto& kSampleFieldNames = kTurnSampleFields;
constexpr const auto& kSampleMembers = kTurnSampleMembers;

// The canonical key order; the parser accepts any order but the writer always uses this one so
// equal turns give byte-identical records.
enum Key : std::size_t {
  k_vehicle_id,
  k_mission_id,
  k_status,
  k_status_reason,
  k_normalized,
  k_commanded_speed_mps,
  k_goal_dheading_deg,
  k_observed_dheading_deg,
  k_initial_heading_deg,
  k_initial_speed_mps,
  k_start_time_s,
  k_end_time_s,
  k_n_warnings,
  k_warnings,
  k_n_samples,
  k_samples,
  // Optional keys: written only when the turn has the value, so records of turns without them
  // read as they always did.
  k_initial_yaw_rate_dps,
  k_speed_after_mps,
  k_key_count,
};
constexpr std::size_t kFirstOptionalKey = k_initial_yaw_rate_dps;
static_assert(k_key_count - kFirstOptionalKey == kTurnOptionalMetaDoubles.size());
static_assert(k_end_time_s - k_commanded_speed_mps + 1 == kTurnMetaDoubles.size());

// The names in Key's order: the turn's own keys (kinematics/turn_keys.hpp) and the record's
// counts of warnings and samples.
constexpr auto kKeyNames = [] {
  std::array<std::string_view, k_key_count> names{};
  names[k_vehicle_id] = kTurnVehicleIdKey;
  names[k_mission_id] = kTurnMissionIdKey;
  names[k_status] = kTurnStatusKey;
  names[k_status_reason] = kTurnStatusReasonKey;
  names[k_normalized] = kTurnNormalizedKey;
  for (std::size_t k = 0; k < kTurnMetaDoubles.size(); ++k)
    names[k_commanded_speed_mps + k] = kTurnMetaDoubles[k].name;
  names[k_n_warnings] = "n_warnings";
  names[k_warnings] = kTurnWarningsKey;
  names[k_n_samples] = "n_samples";
  names[k_samples] = kTurnSamplesKey;
  for (std::size_t k = 0; k < kTurnOptionalMetaDoubles.size(); ++k)
    names[kFirstOptionalKey + k] = kTurnOptionalMetaDoubles[k].name;
  return names;
}();

// ---- writing ----

// Separators and '%' itself must be escaped for the record to split unambiguously; space and
// anything outside printable ASCII are escaped so the record stays one safe token for MOOS.
bool must_escape(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x21 || u > 0x7E || c == '%' || c == ';' || c == '=' || c == ',' || c == '|';
}

void append_encoded(std::string& out, std::string_view s) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (char c : s) {
    if (must_escape(c)) {
      const auto u = static_cast<unsigned char>(c);
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 0x0F];
    } else {
      out += c;
    }
  }
}

void append_double(std::string& out, double v) {
  std::array<char, 32> buf{};  // the longest shortest-round-trip double is 24 characters
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  out.append(buf.data(), r.ptr);
}

void append_key(std::string& out, Key k) {
  out += kKeyNames[k];
  out += '=';
}

// ---- reading ----

struct Located {
  std::string_view value;
  std::size_t offset = 0;  // of value[0] in the line
};

std::string printable_field(std::string_view key) {
  // An unknown key comes from untrusted input: keep the error message short and printable.
  std::string out;
  for (char c : key.substr(0, 64)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u > 0x7E) ? '?' : c;
  }
  return out;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::string decode_string(std::string_view v, std::size_t offset, const std::string& field) {
  std::string out;
  out.reserve(v.size());  // bounded by the input, never by a declared size
  for (std::size_t k = 0; k < v.size(); ++k) {
    const char c = v[k];
    if (c == '%') {
      const int hi = k + 1 < v.size() ? hex_value(v[k + 1]) : -1;
      const int lo = k + 2 < v.size() ? hex_value(v[k + 2]) : -1;
      if (hi < 0 || lo < 0) {
        throw ParseError(field, offset + k, "'%' must be followed by two hex digits");
      }
      out += static_cast<char>(hi * 16 + lo);
      k += 2;
    } else if (must_escape(c)) {
      throw ParseError(field, offset + k,
                       std::string("character '") + c + "' must be percent-encoded");
    } else {
      out += c;
    }
  }
  if (!is_valid_utf8(out)) {
    throw ParseError(field, offset, "string is not valid UTF-8 once percent-decoded");
  }
  return out;
}

struct NumberProblem {
  std::size_t at = 0;  // offset within the value
  const char* message = nullptr;
};

// Returns the problem instead of throwing so the sample loop builds a field name only on error.
std::optional<NumberProblem> read_double(std::string_view v, double& out) {
  if (v.empty()) return NumberProblem{0, "empty value: expected a number"};
  const char* end = v.data() + v.size();
  const auto [p, ec] = std::from_chars(v.data(), end, out);
  if (ec == std::errc::result_out_of_range) {
    return NumberProblem{0, "number is outside the range of a double"};
  }
  if (ec != std::errc{}) return NumberProblem{0, "not a number"};
  // from_chars accepts "nan" and "inf"; the record never holds them (they cannot be validated or
  // written as JSON), so seeing one means the writer was not this code.
  if (!std::isfinite(out)) return NumberProblem{0, "NaN and infinity are not allowed"};
  if (p != end) {
    return NumberProblem{static_cast<std::size_t>(p - v.data()),
                         "trailing characters after number"};
  }
  return std::nullopt;
}

double parse_double(const Located& f, const std::string& field) {
  double d = 0.0;
  if (const auto problem = read_double(f.value, d)) {
    throw ParseError(field, f.offset + problem->at, problem->message);
  }
  return d;
}

std::size_t parse_count(const Located& f, const std::string& field, std::size_t limit) {
  if (f.value.empty()) throw ParseError(field, f.offset, "empty value: expected a count");
  std::uint64_t n = 0;
  const char* end = f.value.data() + f.value.size();
  const auto [p, ec] = std::from_chars(f.value.data(), end, n);
  if (ec == std::errc::result_out_of_range || (ec == std::errc{} && n > limit)) {
    throw ParseError(field, f.offset, "count exceeds the limit of " + std::to_string(limit));
  }
  if (ec != std::errc{}) throw ParseError(field, f.offset, "not a decimal count");
  if (p != end) {
    throw ParseError(field, f.offset + static_cast<std::size_t>(p - f.value.data()),
                     "trailing characters after count");
  }
  return static_cast<std::size_t>(n);
}

std::vector<std::string> parse_warnings(const Located& f, std::size_t declared) {
  std::vector<std::string> out;
  if (declared == 0) {
    if (!f.value.empty()) throw ParseError("warnings", f.offset, "n_warnings=0 but warnings given");
    return out;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = f.value.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? f.value.size() : comma;
    if (out.size() == declared) {
      throw ParseError("warnings", f.offset + start,
                       "more warnings than n_warnings=" + std::to_string(declared));
    }
    out.push_back(decode_string(f.value.substr(start, end - start), f.offset + start,
                                "warnings[" + std::to_string(out.size()) + "]"));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (out.size() != declared) {
    throw ParseError("warnings", f.offset + f.value.size(),
                     "n_warnings=" + std::to_string(declared) + " but " +
                         std::to_string(out.size()) + " warnings given");
  }
  return out;
}

std::vector<TurnSample> parse_samples(const Located& f, std::size_t declared) {
  std::vector<TurnSample> out;
  if (declared == 0) {
    if (!f.value.empty()) throw ParseError("samples", f.offset, "n_samples=0 but samples given");
    return out;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = f.value.find('|', start);
    const std::size_t end = bar == std::string_view::npos ? f.value.size() : bar;
    const std::size_t index = out.size();
    if (index == declared) {
      throw ParseError("samples", f.offset + start,
                       "more samples than n_samples=" + std::to_string(declared));
    }
    const std::string_view text = f.value.substr(start, end - start);
    std::array<std::string_view, kSampleArity> parts;
    std::array<std::size_t, kSampleArity> part_at{};
    std::size_t count = 0;
    std::size_t part_start = 0;
    while (true) {
      const std::size_t comma = text.find(',', part_start);
      const std::size_t part_end = comma == std::string_view::npos ? text.size() : comma;
      if (count == kSampleArity) {
        throw ParseError("samples[" + std::to_string(index) + "]", f.offset + start,
                         "a sample has 5 values (t_s,x_m,y_m,heading_deg,speed_mps); found more");
      }
      parts[count] = text.substr(part_start, part_end - part_start);
      part_at[count] = part_start;
      ++count;
      if (comma == std::string_view::npos) break;
      part_start = comma + 1;
    }
    if (count != kSampleArity) {
      throw ParseError("samples[" + std::to_string(index) + "]", f.offset + start,
                       "a sample has 5 values (t_s,x_m,y_m,heading_deg,speed_mps); found " +
                           std::to_string(count));
    }
    TurnSample s;
    for (std::size_t c = 0; c < kSampleArity; ++c) {
      if (const auto problem = read_double(parts[c], s.*kSampleMembers[c])) {
        throw ParseError("samples[" + std::to_string(index) + "]." + kSampleFieldNames[c],
                         f.offset + start + part_at[c] + problem->at, problem->message);
      }
    }
    out.push_back(s);
    if (bar == std::string_view::npos) break;
    start = bar + 1;
  }
  if (out.size() != declared) {
    throw ParseError("samples", f.offset + f.value.size(),
                     "n_samples=" + std::to_string(declared) + " but " +
                         std::to_string(out.size()) + " samples given");
  }
  return out;
}

}  // namespace

bool is_valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    std::uint32_t cp = 0;
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
      cp = c & 0x1Fu;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      cp = c & 0x0Fu;
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      cp = c & 0x07u;
    } else {
      return false;  // continuation byte, overlong lead 0xC0/0xC1, or past U+10FFFF
    }
    if (s.size() - i < len) return false;
    for (std::size_t k = 1; k < len; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0u) != 0x80u) return false;
      cp = (cp << 6) | (cc & 0x3Fu);
    }
    if (len == 3 && (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF))) return false;
    if (len == 4 && (cp < 0x10000 || cp > 0x10FFFF)) return false;
    i += len;
  }
  return true;
}

void check_turn_serialisable(const TurnSequence& turn) {
  const TurnMeta& m = turn.meta();
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("turn cannot be serialised: " + what);
  };
  if (turn.samples().size() > kMaxTurnRecordSamples) {
    fail(std::to_string(turn.samples().size()) + " samples exceed the limit of " +
         std::to_string(kMaxTurnRecordSamples));
  }
  if (turn.warnings().size() > kMaxTurnRecordWarnings) {
    fail(std::to_string(turn.warnings().size()) + " warnings exceed the limit of " +
         std::to_string(kMaxTurnRecordWarnings));
  }
  for (std::size_t k = 0; k < kTurnMetaDoubles.size(); ++k) {
    if (!std::isfinite(m.*kTurnMetaDoubles[k].member)) {
      fail(std::string(kKeyNames[k_commanded_speed_mps + k]) + " is NaN or infinite");
    }
  }
  for (const auto& [name, ptr] : kTurnOptionalMetaDoubles)
    if (m.*ptr && !std::isfinite(*(m.*ptr))) fail(std::string(name) + " is NaN or infinite");
  if (m.removed_current &&
      !(std::isfinite(m.removed_current->east_mps) && std::isfinite(m.removed_current->north_mps)))
    fail("the removed current is NaN or infinite");
  for (std::size_t i = 0; i < turn.samples().size(); ++i) {
    for (std::size_t c = 0; c < kSampleArity; ++c) {
      if (!std::isfinite(turn.samples()[i].*kSampleMembers[c])) {
        fail("sample " + std::to_string(i) + " " + kSampleFieldNames[c] + " is NaN or infinite");
      }
    }
  }
  if (!turn_status_from_string(to_string(m.status))) fail("status is not ok|aborted|rejected");
  if (!is_valid_utf8(m.vehicle_id)) fail("vehicle_id is not valid UTF-8");
  if (!is_valid_utf8(m.mission_id)) fail("mission_id is not valid UTF-8");
  if (!is_valid_utf8(m.status_reason)) fail("status_reason is not valid UTF-8");
  for (std::size_t i = 0; i < turn.warnings().size(); ++i) {
    if (!is_valid_utf8(turn.warnings()[i])) {
      fail("warning " + std::to_string(i) + " is not valid UTF-8");
    }
  }
}

std::string to_text_record(const TurnSequence& turn) {
  check_turn_serialisable(turn);
  const TurnMeta& m = turn.meta();
  std::string out(kMagic);
  out += std::to_string(kVersion);
  out += ' ';
  const auto string_pair = [&](Key k, const std::string& v) {
    append_key(out, k);
    append_encoded(out, v);
    out += ';';
  };
  string_pair(k_vehicle_id, m.vehicle_id);
  string_pair(k_mission_id, m.mission_id);
  append_key(out, k_status);
  out += to_string(m.status);
  out += ';';
  string_pair(k_status_reason, m.status_reason);
  append_key(out, k_normalized);
  out += m.normalized ? "1;" : "0;";
  for (std::size_t k = 0; k < kTurnMetaDoubles.size(); ++k) {
    append_key(out, static_cast<Key>(k_commanded_speed_mps + k));
    append_double(out, m.*kTurnMetaDoubles[k].member);
    out += ';';
  }
  for (std::size_t k = 0; k < kTurnOptionalMetaDoubles.size(); ++k) {
    const auto ptr = kTurnOptionalMetaDoubles[k].member;
    if (!(m.*ptr)) continue;
    append_key(out, static_cast<Key>(kFirstOptionalKey + k));
    append_double(out, *(m.*ptr));
    out += ';';
  }
  append_key(out, k_n_warnings);
  out += std::to_string(turn.warnings().size());
  out += ';';
  append_key(out, k_warnings);
  for (std::size_t i = 0; i < turn.warnings().size(); ++i) {
    if (i > 0) out += ',';
    append_encoded(out, turn.warnings()[i]);
  }
  out += ';';
  append_key(out, k_n_samples);
  out += std::to_string(turn.samples().size());
  out += ';';
  append_key(out, k_samples);
  for (std::size_t i = 0; i < turn.samples().size(); ++i) {
    if (i > 0) out += '|';
    for (std::size_t c = 0; c < kSampleArity; ++c) {
      if (c > 0) out += ',';
      append_double(out, turn.samples()[i].*kSampleMembers[c]);
    }
  }
  if (out.size() > kMaxTurnRecordBytes) {
    throw std::invalid_argument("turn cannot be serialised: the text record would exceed " +
                                std::to_string(kMaxTurnRecordBytes) + " bytes");
  }
  return out;
}

TurnSequence parse_text_record(std::string_view line) {
  if (line.size() > kMaxTurnRecordBytes) {
    throw ParseError("record", kMaxTurnRecordBytes,
                     "record is longer than " + std::to_string(kMaxTurnRecordBytes) + " bytes");
  }
  if (!line.starts_with(kMagic)) {
    throw ParseError("format", 0, "not a turn record: expected the prefix AVKTURN/");
  }
  const std::size_t version_at = kMagic.size();
  const std::size_t space = line.find(' ', version_at);
  const std::string_view version_text =
      line.substr(version_at, space == std::string_view::npos ? line.npos : space - version_at);
  unsigned version = 0;
  const auto [vp, vec] =
      std::from_chars(version_text.data(), version_text.data() + version_text.size(), version);
  if (version_text.empty() || vec != std::errc{} ||
      vp != version_text.data() + version_text.size()) {
    throw ParseError("version", version_at, "version must be a decimal number");
  }
  if (version != kVersion) {
    throw ParseError("version", version_at,
                     "unsupported version " + std::to_string(version) + "; this reader knows " +
                         std::to_string(kVersion));
  }
  if (space == std::string_view::npos) {
    throw ParseError("version", line.size(), "expected a space after the version");
  }

  std::array<std::optional<Located>, k_key_count> found;
  std::size_t at = space + 1;
  while (true) {
    const std::size_t semi = line.find(';', at);
    const std::size_t end = semi == std::string_view::npos ? line.size() : semi;
    const std::string_view pair = line.substr(at, end - at);
    const std::size_t eq = pair.find('=');
    if (pair.empty()) throw ParseError("record", at, "empty field: expected key=value");
    if (eq == std::string_view::npos) throw ParseError("record", at, "expected key=value");
    const std::string_view key = pair.substr(0, eq);
    std::size_t k = 0;
    while (k < k_key_count && kKeyNames[k] != key)
      ++k;
    if (k == k_key_count) {
      throw ParseError(key.empty() ? "record" : printable_field(key), at,
                       key.empty() ? "empty key" : "unknown key");
    }
    if (found[k]) throw ParseError(std::string(key), at, "duplicate key");
    const Located value{pair.substr(eq + 1), at + eq + 1};
    for (std::size_t b = 0; b < value.value.size(); ++b) {
      const auto u = static_cast<unsigned char>(value.value[b]);
      if (u < 0x21 || u > 0x7E) {
        throw ParseError(std::string(key), value.offset + b,
                         "raw byte " + std::to_string(u) +
                             " in a record: spaces, control and non-ASCII bytes are "
                             "percent-encoded");
      }
    }
    found[k] = value;
    if (semi == std::string_view::npos) break;
    at = semi + 1;
  }
  for (std::size_t k = 0; k < kFirstOptionalKey; ++k) {
    if (!found[k]) throw ParseError(std::string(kKeyNames[k]), line.size(), "missing key");
  }
  const auto field = [&](Key k) -> const Located& { return *found[k]; };
  const auto name = [](Key k) { return std::string(kKeyNames[k]); };

  TurnMeta m;
  m.vehicle_id =
      decode_string(field(k_vehicle_id).value, field(k_vehicle_id).offset, name(k_vehicle_id));
  m.mission_id =
      decode_string(field(k_mission_id).value, field(k_mission_id).offset, name(k_mission_id));
  const auto status = turn_status_from_string(std::string(field(k_status).value));
  if (!status) {
    throw ParseError(name(k_status), field(k_status).offset, "status must be ok|aborted|rejected");
  }
  m.status = *status;
  m.status_reason = decode_string(field(k_status_reason).value, field(k_status_reason).offset,
                                  name(k_status_reason));
  const std::string_view normalized = field(k_normalized).value;
  if (normalized != "0" && normalized != "1") {
    throw ParseError(name(k_normalized), field(k_normalized).offset, "normalized must be 0 or 1");
  }
  m.normalized = normalized == "1";
  for (std::size_t k = 0; k < kTurnMetaDoubles.size(); ++k) {
    const auto key = static_cast<Key>(k_commanded_speed_mps + k);
    m.*kTurnMetaDoubles[k].member = parse_double(field(key), name(key));
  }
  for (std::size_t k = 0; k < kTurnOptionalMetaDoubles.size(); ++k) {
    const auto key = static_cast<Key>(kFirstOptionalKey + k);
    if (found[key]) m.*kTurnOptionalMetaDoubles[k].member = parse_double(field(key), name(key));
  }
  const std::size_t n_warnings =
      parse_count(field(k_n_warnings), name(k_n_warnings), kMaxTurnRecordWarnings);
  std::vector<std::string> warnings = parse_warnings(field(k_warnings), n_warnings);
  const std::size_t n_samples =
      parse_count(field(k_n_samples), name(k_n_samples), kMaxTurnRecordSamples);

  TurnSequence turn(std::move(m), parse_samples(field(k_samples), n_samples));
  for (auto& w : warnings)
    turn.add_warning(std::move(w));
  return turn;
}

}  // namespace avk::kinematics
