#include "app/alog_import.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/context.hpp"
#include "app/store_access.hpp"
#include "kinematics/parse_error.hpp"
#include "kinematics/text_limit.hpp"
#include "kinematics/turn_text.hpp"
#include "mission/helm_mode.hpp"
#include "mission/mission_config.hpp"
#include "store/store.hpp"
#include "vehicle/vehicle.hpp"

namespace avk::app {

namespace {

using kinematics::TurnStatus;

// Navigation rows go to the store in transactions of at most this many: bounded memory, and a
// failure midway leaves whole batches behind, never half of one.
constexpr std::size_t kNavBatchRows = 5000;

class AlogImport {
 public:
  AlogImport(store::Store& db, std::int64_t mission_id, vehicle::AlogNames names,
             mission::TurnExtractorOptions options, const std::string& vehicle_id,
             bool store_extracted)
      : store_extracted_(store_extracted),
        db_(db),
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
    if (!records_seen_ && store_extracted_) {
      for (const auto& t : extracted_) {
        db_.turns().add(mission_id_, t, t.meta().status, t.meta().status_reason);
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
  const store::TurnCounts& from_records() const { return from_records_; }
  const store::TurnCounts& from_extraction() const { return from_extraction_; }
  std::size_t nav_stored() const { return nav_stored_; }
  std::optional<double> last_t_s() const { return last_t_s_; }

 private:
  void on_sample(const vehicle::GuidedNav& s) {
    nav_.push_back({s.nav.t_s, s.nav.x_m, s.nav.y_m, s.nav.heading_deg, s.nav.speed_mps,
                    s.desired_heading_deg, s.desired_speed_mps,
                    std::string(mission::kImportedHelmMode)});
    last_t_s_ = s.nav.t_s;
    if (nav_.size() >= kNavBatchRows) flush_nav();
    if (records_seen_) return;
    if (auto t = extractor_.feed(s)) extracted_.push_back(std::move(*t));
  }

  void flush_nav() {
    if (nav_.empty()) return;
    db_.navigation().append(mission_id_, nav_);
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
        db_.turns().add(mission_id_, turn, turn.meta().status, turn.meta().status_reason);
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

  bool store_extracted_;
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
  store::TurnCounts from_records_, from_extraction_;
};

// The mission's record of how it was imported: enough to import the log again the same way.
std::string import_config(const AlogImportRequest& r) {
  const auto& n = r.names;
  const auto& o = r.extraction;
  return nlohmann::json{{"kind", "import"},
                        {"source", "alog"},
                        {"file", r.source},
                        {"names",
                         {{"NAV_X", n.nav_x},
                          {"NAV_Y", n.nav_y},
                          {"NAV_HEADING", n.nav_heading},
                          {"NAV_SPEED", n.nav_speed},
                          {"DESIRED_HEADING", n.desired_heading},
                          {"DESIRED_SPEED", n.desired_speed},
                          {"TURN_RECORD_RAW", n.turn_record}}},
                        {"extraction",
                         {{"min_step_deg", o.min_step_deg},
                          {"completion_threshold_deg", o.completion.threshold_deg},
                          {"completion_fraction", o.completion.fraction},
                          {"completion_floor_deg", o.completion.floor_deg},
                          {"speed_tolerance_mps", o.condition_set.speed_tolerance_mps},
                          {"max_yaw_rate_dps", o.condition_set.max_yaw_rate_dps},
                          {"window", o.condition_set.window},
                          {"max_gap_s", o.max_gap_s}}}}
      .dump();
}

}  // namespace

Result<AlogImportReport> import_alog(Context& ctx, std::istream& log,
                                     const AlogImportRequest& request) {
  if (const auto why = vehicle::vehicle_id_problem(request.vehicle_id))
    return invalid_argument("vehicle", "the vehicle id " + *why);
  if (const auto why =
          kinematics::text_too_long(request.mission_name, mission::kMaxMissionNameBytes))
    return invalid_argument("name", "the mission's name " + *why);
  store::Store& db = store_of(ctx);
  // The speed limit is not known until the log has been read; 0 says so meanwhile.
  const auto existing = db.vehicles().get(request.vehicle_id);
  vehicle::VehicleInfo info{request.vehicle_id, "alog", existing ? existing->max_speed_mps : 0.0,
                            existing ? existing->length_m : std::nullopt};
  db.vehicles().upsert(info);
  const std::int64_t mission_id =
      db.missions().create(request.vehicle_id, request.mission_name, import_config(request));
  // Running until done: an import that dies midway is listed as interrupted, not as complete.
  db.missions().set_status(mission_id, store::MissionStatus::running, "importing " + request.source,
                           0.0);

  AlogImport import(db, mission_id, request.names, request.extraction, request.vehicle_id,
                    !request.harvest);
  import.run(log);

  if (const auto top = import.nav_stats().max_speed_mps)
    info.max_speed_mps = std::max(info.max_speed_mps, *top);
  db.vehicles().upsert(info);
  db.missions().set_status(mission_id, store::MissionStatus::done,
                           "imported from " + request.source, import.last_t_s().value_or(0.0));
  AlogImportReport r;
  r.mission_id = mission_id;
  r.reader = import.reader_stats();
  r.nav = import.nav_stats();
  r.malformed = import.malformed();
  r.nav_stored = import.nav_stored();
  r.from_records = view_of(import.from_records());
  r.from_extraction = view_of(import.from_extraction());
  if (request.harvest) {
    auto h = harvest_mission(ctx, mission_id);
    if (!h) return h.error();
    r.harvest = std::move(*h);
  }
  return r;
}

}  // namespace avk::app
