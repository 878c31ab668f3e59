#include "app/store_link.hpp"
#include "app/store_writer.hpp"

#include <atomic>
#include <chrono>
#include <functional>
#include <random>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/station_identity.hpp"
#include "kinematics/turn_json.hpp"
#include "store/spool.hpp"

namespace avk::app {

namespace {

using json = nlohmann::json;

// The station's link state, shared by every writer of the process.
struct LinkState {
  std::mutex mutex;
  std::string spool_path;
  bool spooling = false;
  std::string last_error;
  std::int64_t spooled = 0;
  // One replay at a time, across the writers of the process: the spool's order is the order of
  // the writes, and two replays would apply an entry twice.
  std::mutex replay;
};

LinkState& link() {
  static LinkState s;
  return s;
}

std::string default_spool_path() {
  return station_id() + ".spool.db";
}

// A key no other turn of any station has: the station, the moment and randomness.
std::string new_record_key() {
  static std::mutex m;
  static std::mt19937_64 rng{std::random_device{}()};
  std::lock_guard lock(m);
  const auto now = std::chrono::system_clock::now().time_since_epoch().count();
  return station_id() + "-" + std::to_string(now) + "-" + std::to_string(rng());
}

json nav_json(const std::vector<store::NavRow>& rows) {
  json a = json::array();
  for (const auto& r : rows)
    a.push_back({r.t_s, r.x_m, r.y_m, r.heading_deg, r.speed_mps,
                 r.desired_heading_deg ? json(*r.desired_heading_deg) : json(),
                 r.desired_speed_mps ? json(*r.desired_speed_mps) : json(), r.helm_mode});
  return a;
}

std::optional<double> opt(const json& j) {
  return j.is_null() ? std::nullopt : std::optional<double>(j.get<double>());
}

std::vector<store::NavRow> nav_rows(const json& a) {
  std::vector<store::NavRow> rows;
  for (const auto& r : a)
    rows.push_back({r[0].get<double>(), r[1].get<double>(), r[2].get<double>(), r[3].get<double>(),
                    r[4].get<double>(), opt(r[5]), opt(r[6]), r[7].get<std::string>()});
  return rows;
}

// Whether the event is stored already (a replay the station died in the middle of).
bool event_stored(store::Store& db, std::int64_t mission_id, double t_s, const std::string& kind,
                  const std::string& message) {
  std::int64_t after = 0;
  for (;;) {
    const auto page = db.missions().events(mission_id, after, 1000);
    if (page.empty()) return false;
    for (const auto& e : page)
      if (e.t_s == t_s && e.kind == kind && e.message == message) return true;
    after = page.back().id;
  }
}

// Applies one spooled write to the database. Each is recognised when it is stored already, so a
// write replayed again (the station died between storing it and removing it from the spool) is
// not stored twice: a turn by its record key, navigation by the mission's latest time (one
// writer records a mission's navigation in time order), an event or a ConditionSet by its
// fields; a status or a runner written again changes nothing.
void apply(store::Store& db, const store::SpooledWrite& w) {
  const json p = json::parse(w.payload);
  if (w.kind == "nav") {
    const auto rows = nav_rows(p);
    const auto last = db.navigation().last(w.mission_id);
    if (!rows.empty() && last && last->row.t_s >= rows.back().t_s) return;
    db.navigation().append(w.mission_id, rows);
  } else if (w.kind == "turn") {
    db.turns().add(
        w.mission_id, kinematics::turn_from_json(p["raw"]),
        *kinematics::turn_status_from_string(p["status"].get<std::string>()),
        p["reason"].get<std::string>(),
        {opt(p["condition_set_time_s"]), opt(p["heading_error_deg"]), opt(p["yaw_rate_dps"])},
        p["record_key"].get<std::string>());
  } else if (w.kind == "condition_set") {
    const store::ConditionSetTiming c{p["start_s"].get<double>(), p["end_s"].get<double>(),
                                      p["target_speed_mps"].get<double>(),
                                      p["outcome"].get<std::string>()};
    for (const auto& stored : db.missions().condition_sets(w.mission_id))
      if (stored == c) return;
    db.missions().append_condition_set(w.mission_id, c);
  } else if (w.kind == "event") {
    const double t_s = p["t_s"].get<double>();
    const std::string kind = p["kind"].get<std::string>();
    const std::string message = p["message"].get<std::string>();
    if (event_stored(db, w.mission_id, t_s, kind, message)) return;
    db.missions().append_event(w.mission_id, t_s, kind, message);
  } else if (w.kind == "status") {
    db.missions().set_status(w.mission_id,
                             *store::mission_status_from_string(p["status"].get<std::string>()),
                             p["reason"].get<std::string>(), p["t_s"].get<double>());
  } else if (w.kind == "runner") {
    db.missions().set_runner(w.mission_id,
                             p.is_null() ? std::nullopt : std::optional(p.get<std::int64_t>()));
  } else {
    throw store::StoreError("the spool holds a write of unknown kind '" + w.kind + "'");
  }
}

}  // namespace

void set_spool_path(std::string path) {
  std::lock_guard lock(link().mutex);
  link().spool_path = std::move(path);
}

std::string spool_path() {
  std::lock_guard lock(link().mutex);
  return link().spool_path.empty() ? default_spool_path() : link().spool_path;
}

StoreLinkView store_link_view(const std::string& db) {
  StoreLinkView v;
  v.engine = is_database_server(db) ? "postgresql" : "sqlite";
  if (v.engine == "sqlite") return v;
  v.spool_path = spool_path();
  std::lock_guard lock(link().mutex);
  v.spooling = link().spooling;
  v.spooled = link().spooled;
  v.last_error = link().last_error;
  return v;
}

struct StoreWriter::Impl {
  store::Store& db;
  std::unique_ptr<store::Spool> spool;  // null: an SQLite station, which never spools
  std::chrono::steady_clock::time_point last_try{};

  // Writes through `direct`, or spools (kind, mission, payload) when the database is away or
  // writes are already waiting in the spool (they go first: the order is kept). True when
  // written to the database.
  bool write(const char* kind, std::int64_t mission_id, const std::function<json()>& payload,
             const std::function<void()>& direct) {
    if (!spool) {
      direct();
      return true;
    }
    if (replay(false)) {
      try {
        direct();
        return true;
      } catch (const store::StoreUnavailable& e) {
        note_spooling(e.what());
      }
    }
    spool->push(kind, mission_id, payload().dump());
    note_count();
    return false;
  }

  void note_spooling(const std::string& why) {
    std::lock_guard lock(link().mutex);
    link().spooling = true;
    link().last_error = why;
  }
  void note_count() {
    const auto n = spool->count();
    std::lock_guard lock(link().mutex);
    link().spooled = n;
    link().spooling = n > 0;
  }

  // The writes waiting in the spool, as the last push or replay of any writer of the process
  // counted them: a write while connected asks the spool file nothing.
  static std::int64_t waiting() {
    std::lock_guard lock(link().mutex);
    return link().spooled;
  }

  // True when the spool is empty (replayed now or nothing waited).
  bool replay(bool now) {
    if (waiting() == 0) return true;
    std::lock_guard order(link().replay);
    if (spool->count() == 0) {
      note_count();
      return true;
    }
    const auto t = std::chrono::steady_clock::now();
    if (!now && t - last_try < std::chrono::seconds(1)) return false;
    last_try = t;
    try {
      while (auto w = spool->oldest()) {
        apply(db, *w);
        // A crash between the write and this removal replays the write again: apply recognises
        // it as stored.
        spool->remove(w->seq);
      }
    } catch (const store::StoreUnavailable& e) {
      note_spooling(e.what());
      note_count();
      return false;
    }
    note_count();
    return true;
  }
};

StoreWriter::StoreWriter(store::Store& db) : impl_(std::make_unique<Impl>(Impl{db, nullptr, {}})) {
  if (db.engine() == store::Engine::postgresql) {
    impl_->spool = std::make_unique<store::Spool>(spool_path());
    // What an earlier run left in the spool waits before anything this writer writes.
    impl_->note_count();
  }
}

StoreWriter::~StoreWriter() = default;

void StoreWriter::nav(std::int64_t mission_id, const std::vector<store::NavRow>& rows) {
  impl_->write(
      "nav", mission_id, [&] { return nav_json(rows); },
      [&] { impl_->db.navigation().append(mission_id, rows); });
}

std::optional<std::int64_t> StoreWriter::turn(std::int64_t mission_id,
                                              const kinematics::TurnSequence& raw,
                                              kinematics::TurnStatus status,
                                              const std::string& reason,
                                              const store::TurnStart& start) {
  const std::string key = impl_->spool ? new_record_key() : std::string();
  std::optional<std::int64_t> id;
  impl_->write(
      "turn", mission_id,
      [&] {
        return json{{"raw", kinematics::to_json(raw)},
                    {"status", kinematics::to_string(status)},
                    {"reason", reason},
                    {"condition_set_time_s",
                     start.condition_set_time_s ? json(*start.condition_set_time_s) : json()},
                    {"heading_error_deg",
                     start.heading_error_deg ? json(*start.heading_error_deg) : json()},
                    {"yaw_rate_dps", start.yaw_rate_dps ? json(*start.yaw_rate_dps) : json()},
                    {"record_key", key}};
      },
      [&] { id = impl_->db.turns().add(mission_id, raw, status, reason, start, key); });
  return id;
}

void StoreWriter::condition_set(std::int64_t mission_id, const store::ConditionSetTiming& c) {
  impl_->write(
      "condition_set", mission_id,
      [&] {
        return json{{"start_s", c.start_s},
                    {"end_s", c.end_s},
                    {"target_speed_mps", c.target_speed_mps},
                    {"outcome", c.outcome}};
      },
      [&] { impl_->db.missions().append_condition_set(mission_id, c); });
}

void StoreWriter::event(std::int64_t mission_id, double t_s, const std::string& kind,
                        const std::string& message) {
  impl_->write(
      "event", mission_id,
      [&] {
        return json{{"t_s", t_s}, {"kind", kind}, {"message", message}};
      },
      [&] { impl_->db.missions().append_event(mission_id, t_s, kind, message); });
}

void StoreWriter::status(std::int64_t mission_id, store::MissionStatus s, const std::string& reason,
                         double t_s) {
  impl_->write(
      "status", mission_id,
      [&] {
        return json{{"status", store::to_string(s)}, {"reason", reason}, {"t_s", t_s}};
      },
      [&] { impl_->db.missions().set_status(mission_id, s, reason, t_s); });
}

void StoreWriter::runner(std::int64_t mission_id, std::optional<std::int64_t> pid) {
  impl_->write(
      "runner", mission_id, [&] { return pid ? json(*pid) : json(); },
      [&] { impl_->db.missions().set_runner(mission_id, pid); });
}

bool StoreWriter::replay(bool now) {
  return !impl_->spool || impl_->replay(now);
}

}  // namespace avk::app
