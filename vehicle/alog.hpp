#pragma once
// MOOS-IvP .alog files (pLogger): one posting a line, `<time> <VARIABLE> <source> <value>`,
// separated by runs of spaces or tabs; the value is the rest of the line and may hold spaces.
// `%` lines are the header. Format and import rules: docs/alog-import.md.
//
// Logs run to hundreds of MB, so the reader streams: it holds one buffer, never the file, and a
// malformed line is counted and skipped, never fatal (years-old logs have torn last lines).

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vehicle/vehicle.hpp"

namespace avk::vehicle {

inline constexpr std::size_t kAlogMaxLineBytes = std::size_t{64} << 10;
inline constexpr std::size_t kAlogReportedProblems = 10;
// pLogger stamps every posting in seconds from the log start, and a running MOOS community posts
// navigation several times a second, so a posting stamped this far past the newest one so far
// (or before the start) is corrupt, not late: taking it as the newest time would make every later
// posting look older than it.
inline constexpr double kAlogMaxTimeJump_s = 6.0 * 3600.0;

struct AlogEntry {
  double t_s = 0.0;  // seconds from the log start
  std::string variable;
  std::string source;
  std::string value;
  std::size_t line = 0;  // 1-based
};

struct AlogProblem {
  std::size_t line = 0;
  std::string reason;
};

// A count of malformed lines and the first few of them, so a report can point at them without
// keeping millions of reasons for a badly broken log.
struct AlogProblems {
  std::size_t count = 0;
  std::vector<AlogProblem> first;  // the lowest line numbers, at most kAlogReportedProblems

  void add(std::size_t line, std::string reason);
  // Adds another list's count and keeps the lowest line numbers of both.
  void merge(const AlogProblems& other);
};

struct AlogStats {
  std::size_t lines = 0;
  std::size_t bytes = 0;
  std::size_t header_lines = 0;
  std::size_t blank_lines = 0;
  std::size_t entries = 0;
  AlogProblems malformed;
};

class AlogReader {
 public:
  explicit AlogReader(std::istream& in, std::size_t max_line_bytes = kAlogMaxLineBytes);

  // The next well-formed posting; false at the end of the input. Reusing one entry lets its
  // strings keep their capacity, so a long log is read without an allocation a line.
  bool next(AlogEntry& entry);
  const AlogStats& stats() const { return stats_; }

 private:
  // The next line without its end of line; false at the end. Sets oversized for a line longer
  // than the limit, whose bytes were skipped.
  bool next_line(std::string_view& line, bool& oversized);
  bool parse(std::string_view line, AlogEntry& entry);

  std::istream& in_;
  std::size_t max_line_bytes_;
  std::vector<char> buffer_;
  double newest_t_s_ = 0.0;  // the latest time of a posting read, from the log start
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  AlogStats stats_;
};

// Variable names the navigation builder listens to. Vehicles log under their own names
// (NAV_X_GPS, M200_HEADING, ...); the defaults are the MOOS-IvP ones.
struct AlogNames {
  std::string nav_x = "NAV_X";
  std::string nav_y = "NAV_Y";
  std::string nav_heading = "NAV_HEADING";
  std::string nav_speed = "NAV_SPEED";
  std::string desired_heading = "DESIRED_HEADING";
  std::string desired_speed = "DESIRED_SPEED";
  std::string turn_record = "TURN_RECORD_RAW";
};

// Applies overrides written `NAV_X=GPS_X,NAV_HEADING=COMPASS_HEADING`: each key is a default
// name. Throws std::invalid_argument naming an unknown key, a duplicate or an empty name.
AlogNames parse_alog_names(std::string_view overrides, AlogNames names = {});

// A navigation sample with the guidance in force when it was taken.
struct GuidedNav {
  NavSample nav;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
};

struct AlogPosting {
  double t_s = 0.0;
  std::string value;
  std::size_t line = 0;
};

struct AlogNavStats {
  std::size_t samples = 0;
  // Groups of NAV_* postings without all of x, y and heading: no sample can be made of them.
  std::size_t incomplete_groups = 0;
  std::size_t turn_records = 0;
  std::optional<double> max_speed_mps;  // the largest NAV_SPEED posted
  AlogProblems malformed;               // values that are not finite numbers, time going back
};

// Turns the asynchronous postings into navigation samples. NAV_* postings stamped within 1 ms of
// each other are one group; the group becomes a sample when a later posting closes it, if it has
// x, y and heading (speed is the latest posted, 0 before any). DESIRED_* are sample-and-hold, as
// MOOS mail is: a sample carries the latest posted at or before its time, or none.
class AlogNavBuilder {
 public:
  explicit AlogNavBuilder(AlogNames names = {});

  // Feeds one posting; true when it closed a group that became a sample (written to out).
  bool feed(const AlogEntry& entry, GuidedNav& out);
  // Closes the last group at the end of the log.
  bool finish(GuidedNav& out);

  // The turn record postings collected since the last call, oldest first.
  std::vector<AlogPosting> take_turn_records();
  const AlogNavStats& stats() const { return stats_; }
  const AlogNames& names() const { return names_; }

 private:
  enum class Field { x, y, heading, speed, desired_heading, desired_speed, turn_record, other };
  Field classify(std::string_view variable) const;
  bool close_group(GuidedNav& out);

  AlogNames names_;
  AlogNavStats stats_;
  std::vector<AlogPosting> turn_records_;
  std::optional<double> group_t_s_;
  std::optional<double> x_m_, y_m_, heading_deg_;
  std::optional<double> speed_mps_;
  std::optional<double> desired_heading_deg_, desired_speed_mps_;
  std::optional<double> last_sample_t_s_;
};

}  // namespace avk::vehicle
