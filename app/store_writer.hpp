#pragma once
// The write path of a running mission (app/store_link.hpp): to the database, or to the local
// spool while a PostgreSQL server is away, replayed in order when it is back. A turn is written
// under a key of its own (store::TurnRepository::add's record_key), so a turn whose commit's fate
// was unknown and that is replayed is never stored twice. For app/ only: it holds a store.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/turn_sequence.hpp"
#include "store/store.hpp"

namespace avk::app {

// Writes to the database, or to the spool while the database cannot be reached: every write of a
// running mission goes through one of these.
class StoreWriter {
 public:
  explicit StoreWriter(store::Store& db);
  ~StoreWriter();

  void nav(std::int64_t mission_id, const std::vector<store::NavRow>& rows);
  // The stored turn's id; none while the turn waits in the spool.
  std::optional<std::int64_t> turn(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                                   kinematics::TurnStatus status, const std::string& reason,
                                   const store::TurnStart& start);
  void condition_set(std::int64_t mission_id, const store::ConditionSetTiming& c);
  void event(std::int64_t mission_id, double t_s, const std::string& kind,
             const std::string& message);
  void status(std::int64_t mission_id, store::MissionStatus s, const std::string& reason,
              double t_s);
  void runner(std::int64_t mission_id, std::optional<std::int64_t> pid);

  // Replays the spool if the database is back (at most once a second unless `now`); true when
  // nothing is left in it.
  bool replay(bool now = false);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace avk::app
