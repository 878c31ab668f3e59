// `avk import alog`: a MOOS-IvP log into the store as a mission of its own (docs/alog-import.md).
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "kinematics/parse_error.hpp"
#include "kinematics/turn_text.hpp"
#include "mission/turn_extractor.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/serialize.hpp"
#include "store/store.hpp"
#include "vehicle/alog.hpp"

namespace avk::server {

namespace {

using kinematics::TurnStatus;

// Navigation rows go to the store in transactions of at most this many: bounded memory, and a
// failure midway leaves whole batches behind, never half of one.
constexpr std::size_t kNavBatchRows = 5000;
constexpr std::size_t kProblemsShown = 5;

struct TurnCounts {
  std::size_t ok = 0, aborted = 0, rejected = 0;
  std::size_t total() const { return ok + aborted + rejected; }
  void add(TurnStatus s) {
    (s == TurnStatus::ok ? ok : s == TurnStatus::aborted ? aborted : rejected)++;
  }
};

std::string counts_text(const TurnCounts& c) {
  return std::to_string(c.ok) + " ok, " + std::to_string(c.aborted) + " aborted, " +
         std::to_string(c.rejected) + " rejected";
}

class AlogImport {
 public:
  AlogImport(store::Store& db, std::int64_t mission_id, vehicle::AlogNames names,
             mission::TurnExtractorOptions options, const std::string& vehicle_id)
      : db_(db),
        mission_id_(mission_id),
        builder_(std::move(names)),
        extractor_(options, vehicle_id, std::to_string(mission_id)) {
    nav_.reserve(kNavBatchRows);
  }

  void run(std::istream& in) {
    vehicle::AlogReader reader(in);
    vehicle::AlogEntry entry;
    vehicle::GuidedNav sample;
    while (reader.next(entry)) {
      if (builder_.feed(entry, sample)) on_sample(sample);
      if (builder_.stats().turn_records > records_taken_) store_records();
    }
    if (builder_.finish(sample)) on_sample(sample);
    if (auto t = extractor_.finish()) extracted_.push_back(std::move(*t));
    flush_nav();
    // Turn records, when the log has any, are what the mission recorded; extraction is only
    // for logs without them.
    if (!records_seen_) {
      for (const auto& t : extracted_) {
        db_.store_turn(mission_id_, t, t.meta().status, t.meta().status_reason);
        from_extraction_.add(t.meta().status);
      }
    }
    extracted_.clear();
    stats_ = reader.stats();
    malformed_ = stats_.malformed;
    malformed_.merge(builder_.stats().malformed);
    malformed_.merge(record_problems_);
  }

  const vehicle::AlogStats& reader_stats() const { return stats_; }
  const vehicle::AlogNavStats& nav_stats() const { return builder_.stats(); }
  const vehicle::AlogProblems& malformed() const { return malformed_; }
  const TurnCounts& from_records() const { return from_records_; }
  const TurnCounts& from_extraction() const { return from_extraction_; }
  std::size_t nav_stored() const { return nav_stored_; }
  std::optional<double> last_t_s() const { return last_t_s_; }

 private:
  void on_sample(const vehicle::GuidedNav& s) {
    nav_.push_back({s.nav.t_s, s.nav.x_m, s.nav.y_m, s.nav.heading_deg, s.nav.speed_mps,
                    s.desired_heading_deg, s.desired_speed_mps, "IMPORTED"});
    last_t_s_ = s.nav.t_s;
    if (nav_.size() >= kNavBatchRows) flush_nav();
    if (records_seen_) return;
    if (auto t = extractor_.feed(s)) extracted_.push_back(std::move(*t));
  }

  void flush_nav() {
    if (nav_.empty()) return;
    db_.append_nav(mission_id_, nav_);
    nav_stored_ += nav_.size();
    nav_.clear();
  }

  void store_records() {
    const auto records = builder_.take_turn_records();
    records_taken_ += records.size();
    if (!records_seen_) {
      records_seen_ = true;
      extracted_.clear();  // never stored: the records replace them
      extracted_.shrink_to_fit();
    }
    for (const auto& r : records) {
      kinematics::TurnSequence turn;
      try {
        turn = kinematics::parse_text_record(r.value);
      } catch (const kinematics::ParseError& e) {
        record_problems_.add(r.line, "turn record: " + std::string(e.what()));
        continue;
      }
      try {
        db_.store_turn(mission_id_, turn, turn.meta().status, turn.meta().status_reason);
      } catch (const kinematics::TurnError& e) {
        // An ok record that cannot be normalised; a database failure still ends the import.
        record_problems_.add(r.line, "turn record cannot be stored: " + std::string(e.what()));
        continue;
      } catch (const std::invalid_argument& e) {
        record_problems_.add(r.line, "turn record cannot be stored: " + std::string(e.what()));
        continue;
      }
      from_records_.add(turn.meta().status);
    }
  }

  store::Store& db_;
  std::int64_t mission_id_;
  vehicle::AlogNavBuilder builder_;
  mission::TurnExtractor extractor_;
  std::vector<store::NavRow> nav_;
  std::size_t nav_stored_ = 0;
  std::optional<double> last_t_s_;
  // Extracted turns wait for the end of the log: a turn record anywhere in it replaces them.
  // A turn is a few kB, so even thousands of them are far less than the log.
  std::vector<kinematics::TurnSequence> extracted_;
  bool records_seen_ = false;
  std::size_t records_taken_ = 0;
  vehicle::AlogProblems record_problems_;
  vehicle::AlogStats stats_;
  vehicle::AlogProblems malformed_;
  TurnCounts from_records_, from_extraction_;
};

const std::set<std::string> kAlogValues = {
    "db", "vehicle", "names", "turn-record", "threshold", "speed-tolerance", "max-yaw-rate"};

double positive(const Args& a, const std::string& name, double fallback) {
  const double v = a.number(name).value_or(fallback);
  if (!(v > 0.0)) throw UsageError("--" + name + " must be positive");
  return v;
}

int import_alog(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, kAlogValues);
  if (a.positional().size() != 1) throw UsageError("expected one .alog file");
  const std::string path = a.positional()[0];
  const std::string db_path = a.require("db");
  vehicle::AlogNames names;
  try {
    names = vehicle::parse_alog_names(a.get("names").value_or(""));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--names: ") + e.what());
  }
  if (const auto v = a.get("turn-record")) {
    if (v->empty() || v->find_first_of(" \t") != std::string::npos)
      throw UsageError("--turn-record needs a variable name");
    names.turn_record = *v;
  }
  mission::TurnExtractorOptions options;
  options.completion_threshold_deg = positive(a, "threshold", options.completion_threshold_deg);
  options.condition_set.speed_tolerance_mps =
      positive(a, "speed-tolerance", options.condition_set.speed_tolerance_mps);
  options.condition_set.max_yaw_rate_dps =
      positive(a, "max-yaw-rate", options.condition_set.max_yaw_rate_dps);
  const std::filesystem::path file(path);
  const std::string vehicle_id = a.get("vehicle").value_or(file.stem().string());
  if (vehicle_id.empty()) throw UsageError("--vehicle must not be empty");

  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(file, ec)) in.open(file, std::ios::binary);
  if (!in.is_open() || !in) {
    io.err << "avk import: cannot open '" << path << "': "
           << (std::filesystem::is_directory(file, ec) ? "is a directory" : std::strerror(errno))
           << "\n";
    return 1;
  }

  const nlohmann::json config = {
      {"kind", "import"},
      {"source", "alog"},
      {"file", path},
      {"names",
       {{"NAV_X", names.nav_x},
        {"NAV_Y", names.nav_y},
        {"NAV_HEADING", names.nav_heading},
        {"NAV_SPEED", names.nav_speed},
        {"DESIRED_HEADING", names.desired_heading},
        {"DESIRED_SPEED", names.desired_speed},
        {"TURN_RECORD_RAW", names.turn_record}}},
      {"extraction",
       {{"min_step_deg", options.min_step_deg},
        {"completion_threshold_deg", options.completion_threshold_deg},
        {"speed_tolerance_mps", options.condition_set.speed_tolerance_mps},
        {"max_yaw_rate_dps", options.condition_set.max_yaw_rate_dps},
        {"window", options.condition_set.window},
        {"max_gap_s", options.max_gap_s}}}};

  store::Store db(db_path);
  // The speed limit is not known until the log has been read; 0 says so meanwhile.
  const auto existing = db.get_vehicle(vehicle_id);
  vehicle::VehicleInfo info{vehicle_id, "alog", existing ? existing->max_speed_mps : 0.0,
                            existing ? existing->length_m : std::nullopt};
  db.upsert_vehicle(info);
  const std::int64_t mission_id =
      db.create_mission(vehicle_id, file.filename().string(), config.dump());
  // Running until done: an import that dies midway is listed as interrupted, not as complete.
  db.set_mission_status(mission_id, store::MissionStatus::running, "importing " + path, 0.0);

  AlogImport import(db, mission_id, names, options, vehicle_id);
  import.run(in);

  if (const auto top = import.nav_stats().max_speed_mps)
    info.max_speed_mps = std::max(info.max_speed_mps, *top);
  db.upsert_vehicle(info);
  db.set_mission_status(mission_id, store::MissionStatus::done, "imported from " + path,
                        import.last_t_s().value_or(0.0));

  const auto& rs = import.reader_stats();
  const auto& ns = import.nav_stats();
  const auto& bad = import.malformed();
  io.out << "imported " << path << " as mission " << mission_id << " of vehicle " << vehicle_id
         << "\n";
  io.out << "lines: " << rs.lines << " read (" << rs.bytes << " bytes), " << rs.header_lines
         << " header, " << rs.blank_lines << " blank, " << rs.entries << " postings, " << bad.count
         << " malformed\n";
  for (std::size_t i = 0; i < bad.first.size() && i < kProblemsShown; ++i)
    io.out << "  line " << bad.first[i].line << ": " << bad.first[i].reason << "\n";
  if (bad.count > kProblemsShown) io.out << "  ... and " << bad.count - kProblemsShown << " more\n";
  io.out << "navigation: " << import.nav_stored() << " samples stored";
  if (ns.incomplete_groups)
    io.out << ", " << ns.incomplete_groups << " groups without x, y and heading skipped";
  if (ns.max_speed_mps) io.out << "; top speed " << fixed(*ns.max_speed_mps, 2) << " m/s";
  io.out << "\n";
  const TurnCounts& rec = import.from_records();
  const TurnCounts& ext = import.from_extraction();
  io.out << "turns: " << rec.total() + ext.total() << " stored\n";
  io.out << "  from turn records (" << names.turn_record << "): " << rec.total() << " ("
         << counts_text(rec) << ")\n";
  io.out << "  extracted from desired heading steps: " << ext.total() << " (" << counts_text(ext)
         << ")" << (ns.turn_records ? "; not used: the log has turn records" : "") << "\n";
  io.out << "mission " << mission_id << " done\n";
  return 0;
}

}  // namespace

int cmd_import(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'import alog FILE --db FILE'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "alog") return import_alog(rest, io);
  throw UsageError("unknown subcommand 'import " + args[0] + "'");
}

}  // namespace avk::server
