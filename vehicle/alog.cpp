#include "vehicle/alog.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <istream>
#include <limits>
#include <stdexcept>

#include "vehicle/nav_ranges.hpp"

namespace avk::vehicle {

namespace {

// Postings of one navigation report are stamped within this of each other; pLogger writes
// milliseconds at best.
constexpr double kGroupTolerance_s = 1e-3;

// Large enough that a refill is rare, and always more than a longest line, so a line that fits
// the limit always fits the buffer.
constexpr std::size_t kMinBufferBytes = std::size_t{1} << 20;

bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (is_blank(s.front()) || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (is_blank(s.back()) || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// The next run of non-blank characters; s is left at what follows it.
std::string_view take_field(std::string_view& s) {
  std::size_t i = 0;
  while (i < s.size() && is_blank(s[i]))
    ++i;
  std::size_t j = i;
  while (j < s.size() && !is_blank(s[j]))
    ++j;
  const std::string_view field = s.substr(i, j - i);
  s.remove_prefix(j);
  return field;
}

std::optional<double> finite_number(std::string_view s) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Quotes a value in a reason without letting a garbage line flood the report.
std::string quoted(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  out += s.substr(0, kMax);
  if (s.size() > kMax) out += "...";
  out += "'";
  return out;
}

}  // namespace

void AlogProblems::add(std::size_t line, std::string reason) {
  ++count;
  if (first.size() < kAlogReportedProblems) {
    first.push_back({line, std::move(reason)});
  } else if (line < first.back().line) {
    first.back() = {line, std::move(reason)};
  } else {
    return;
  }
  std::sort(first.begin(), first.end(),
            [](const AlogProblem& a, const AlogProblem& b) { return a.line < b.line; });
}

void AlogProblems::merge(const AlogProblems& other) {
  const std::size_t total = count + other.count;
  for (const AlogProblem& p : other.first)
    add(p.line, p.reason);
  count = total;
}

AlogReader::AlogReader(std::istream& in, std::size_t max_line_bytes)
    : in_(in),
      max_line_bytes_(max_line_bytes),
      buffer_(std::max(kMinBufferBytes, 2 * max_line_bytes + 2)) {}

bool AlogReader::next_line(std::string_view& line, bool& oversized) {
  oversized = false;
  std::size_t scanned = begin_;  // bytes before this hold no newline
  for (;;) {
    if (const void* nl = std::memchr(buffer_.data() + scanned, '\n', end_ - scanned)) {
      const std::size_t at =
          static_cast<std::size_t>(static_cast<const char*>(nl) - buffer_.data());
      line = std::string_view(buffer_.data() + begin_, at - begin_);
      stats_.bytes += at + 1 - begin_;
      begin_ = at + 1;
      if (line.size() > max_line_bytes_) oversized = true;
      return true;
    }
    if (eof_) {
      if (begin_ == end_ && !oversized) return false;
      // A last line without a newline is still a line.
      line = std::string_view(buffer_.data() + begin_, end_ - begin_);
      stats_.bytes += end_ - begin_;
      begin_ = end_;
      if (line.size() > max_line_bytes_) oversized = true;
      return true;
    }
    if (end_ - begin_ > max_line_bytes_) {
      // Far too long to be a posting: drop what is buffered and keep looking for its end, so
      // a corrupt stretch of a log (binary junk without newlines) never grows the buffer.
      oversized = true;
      stats_.bytes += end_ - begin_;
      begin_ = end_ = 0;
    } else if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    scanned = end_;
    in_.read(buffer_.data() + end_, static_cast<std::streamsize>(buffer_.size() - end_));
    const auto got = static_cast<std::size_t>(in_.gcount());
    end_ += got;
    if (got == 0 || !in_) eof_ = true;
  }
}

bool AlogReader::next(AlogEntry& entry) {
  std::string_view line;
  bool oversized = false;
  while (next_line(line, oversized)) {
    ++stats_.lines;
    if (oversized) {
      stats_.malformed.add(stats_.lines,
                           "line longer than " + std::to_string(max_line_bytes_) + " bytes");
      continue;
    }
    if (parse(line, entry)) {
      ++stats_.entries;
      return true;
    }
  }
  return false;
}

bool AlogReader::parse(std::string_view line, AlogEntry& entry) {
  std::string_view rest = trim(line);
  if (rest.empty()) {
    ++stats_.blank_lines;
    return false;
  }
  if (rest.front() == '%') {
    ++stats_.header_lines;
    return false;
  }
  const std::string_view time = take_field(rest);
  const std::string_view variable = take_field(rest);
  const std::string_view source = take_field(rest);
  const std::string_view value = trim(rest);
  if (value.empty()) {
    stats_.malformed.add(stats_.lines, "expected time, variable, source and value");
    return false;
  }
  const auto t = finite_number(time);
  if (!t) {
    stats_.malformed.add(stats_.lines, "time " + quoted(time) + " is not a finite number");
    return false;
  }
  if (*t < 0.0) {
    stats_.malformed.add(stats_.lines, "time " + quoted(time) + " is before the log start");
    return false;
  }
  if (*t > newest_t_s_ + kAlogMaxTimeJump_s) {
    stats_.malformed.add(
        stats_.lines,
        "time " + quoted(time) + " s is more than 6 h after the newest posting before it");
    return false;
  }
  newest_t_s_ = std::max(newest_t_s_, *t);
  entry.t_s = *t;
  entry.variable.assign(variable);
  entry.source.assign(source);
  entry.value.assign(value);
  entry.line = stats_.lines;
  return true;
}

AlogNames parse_alog_names(std::string_view overrides, AlogNames names) {
  const AlogNames defaults;
  const std::pair<const std::string*, std::string*> keys[] = {
      {&defaults.nav_x, &names.nav_x},
      {&defaults.nav_y, &names.nav_y},
      {&defaults.nav_heading, &names.nav_heading},
      {&defaults.nav_speed, &names.nav_speed},
      {&defaults.desired_heading, &names.desired_heading},
      {&defaults.desired_speed, &names.desired_speed},
      {&defaults.turn_record, &names.turn_record},
  };
  std::vector<std::string_view> seen;
  while (!overrides.empty()) {
    const std::size_t comma = overrides.find(',');
    const std::string_view item = overrides.substr(0, comma);
    overrides.remove_prefix(comma == std::string_view::npos ? overrides.size() : comma + 1);
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos)
      throw std::invalid_argument("expected NAME=VARIABLE, got '" + std::string(item) + "'");
    const std::string_view key = item.substr(0, eq);
    const std::string_view value = item.substr(eq + 1);
    const auto it = std::find_if(std::begin(keys), std::end(keys),
                                 [&](const auto& k) { return *k.first == key; });
    if (it == std::end(keys))
      throw std::invalid_argument("unknown name '" + std::string(key) + "'");
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      throw std::invalid_argument("name '" + std::string(key) + "' given twice");
    if (value.empty() || value.find_first_of(" \t") != std::string_view::npos)
      throw std::invalid_argument("name '" + std::string(key) + "' needs a variable name");
    seen.push_back(key);
    it->second->assign(value);
  }
  return names;
}

AlogNavBuilder::AlogNavBuilder(AlogNames names) : names_(std::move(names)) {}

AlogNavBuilder::Field AlogNavBuilder::classify(std::string_view v) const {
  if (v == names_.nav_x) return Field::x;
  if (v == names_.nav_y) return Field::y;
  if (v == names_.nav_heading) return Field::heading;
  if (v == names_.nav_speed) return Field::speed;
  if (v == names_.desired_heading) return Field::desired_heading;
  if (v == names_.desired_speed) return Field::desired_speed;
  if (v == names_.turn_record) return Field::turn_record;
  return Field::other;
}

bool AlogNavBuilder::close_group(GuidedNav& out) {
  if (!group_t_s_) return false;
  const double t = *group_t_s_;
  group_t_s_.reset();
  const bool complete = x_m_ && y_m_ && heading_deg_;
  if (complete) {
    out.nav = NavSample{};
    out.nav.t_s = t;
    out.nav.x_m = *x_m_;
    out.nav.y_m = *y_m_;
    out.nav.heading_deg = *heading_deg_;
    out.nav.speed_mps = speed_mps_.value_or(0.0);
    out.desired_heading_deg = desired_heading_deg_;
    out.desired_speed_mps = desired_speed_mps_;
    last_sample_t_s_ = t;
    ++stats_.samples;
  } else {
    ++stats_.incomplete_groups;
  }
  x_m_.reset();
  y_m_.reset();
  heading_deg_.reset();
  return complete;
}

bool AlogNavBuilder::feed(const AlogEntry& e, GuidedNav& out) {
  const Field f = classify(e.variable);
  if (f == Field::other) return false;
  if (f == Field::turn_record) {
    turn_records_.push_back({e.t_s, e.value, e.line});
    ++stats_.turn_records;
    return false;
  }
  const auto v = finite_number(e.value);
  if (!v) {
    stats_.malformed.add(e.line,
                         e.variable + " value " + quoted(e.value) + " is not a finite number");
    return false;
  }
  // The ranges every reader of navigation holds, so that an imported log exports and imports
  // again.
  const ValueRange& range = f == Field::x || f == Field::y                       ? kGridRange_m
                            : f == Field::heading || f == Field::desired_heading ? kHeadingRange_deg
                                                                                 : kSpeedRange_mps;
  if (!range.contains(*v)) {
    stats_.malformed.add(
        e.line, e.variable + " value " + quoted(e.value) + " is out of range " + to_string(range));
    return false;
  }
  const bool is_nav = f == Field::x || f == Field::y || f == Field::heading || f == Field::speed;
  // pLogger writes mail as it arrives, so stamps may step back a little; a navigation posting
  // from before the sample already made cannot be placed and would make time run backwards.
  const double floor_s = group_t_s_
                             ? *group_t_s_
                             : last_sample_t_s_.value_or(-std::numeric_limits<double>::infinity());
  if (is_nav && e.t_s < floor_s - kGroupTolerance_s) {
    stats_.malformed.add(e.line, e.variable + " at " + std::to_string(e.t_s) +
                                     " s is older than the navigation before it");
    return false;
  }
  bool emitted = false;
  if (group_t_s_ && e.t_s > *group_t_s_ + kGroupTolerance_s) emitted = close_group(out);
  switch (f) {
    case Field::x:
      x_m_ = *v;
      break;
    case Field::y:
      y_m_ = *v;
      break;
    case Field::heading:
      heading_deg_ = *v;
      break;
    case Field::speed:
      speed_mps_ = *v;
      stats_.max_speed_mps = std::max(stats_.max_speed_mps.value_or(*v), *v);
      break;
    case Field::desired_heading:
      desired_heading_deg_ = *v;
      break;
    case Field::desired_speed:
      desired_speed_mps_ = *v;
      break;
    default:
      break;
  }
  // Speed alone makes no sample; it is taken as the latest by the next group.
  if (is_nav && f != Field::speed && !group_t_s_) group_t_s_ = e.t_s;
  return emitted;
}

bool AlogNavBuilder::finish(GuidedNav& out) {
  return close_group(out);
}

std::vector<AlogPosting> AlogNavBuilder::take_turn_records() {
  std::vector<AlogPosting> out;
  out.swap(turn_records_);
  return out;
}

}  // namespace avk::vehicle
