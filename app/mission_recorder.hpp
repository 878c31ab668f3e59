#pragma once
// Keeps everything a running mission records in the store: navigation in batches (a crash loses
// at most the last second of it), each turn in one transaction the moment it ends, ConditionSet
// episodes, events and status changes; and the mission's current, estimated again at every turn
// (app/current_tracker.hpp). On a database server every write goes through a StoreWriter
// (app/store_link.hpp): while the server is away the mission records into the local spool.

#include <cstdint>
#include <optional>
#include <vector>

#include "app/current_tracker.hpp"
#include "app/store_writer.hpp"
#include "mission/mission_observer.hpp"
#include "store/store.hpp"

namespace avk::app {

store::MissionStatus to_store_status(mission::MissionState s);

class MissionRecorder final : public mission::MissionObserver {
 public:
  // on_current hears every new estimate of the mission's current (the live stream's).
  MissionRecorder(store::Store& store, std::int64_t mission_id, double flush_period_s = 1.0,
                  CurrentTracker::Publish on_current = {});
  ~MissionRecorder() override;

  void on_nav(const mission::NavRecord& r) override;
  void on_turn_started(const mission::TurnTask& task, const mission::RunningTurn& turn) override;
  void on_turn(mission::TurnOutcome& t) override;
  void on_condition_set(const mission::ConditionSetEpisode& e) override;
  void on_event(const mission::MissionEventRecord& e) override;
  void on_state(mission::MissionState s, const std::string& reason, double t_s) override;

  void flush();
  // The process running the mission (none: no longer run).
  void set_runner(std::optional<std::int64_t> pid);
  // Writes the spool to the database if it is back; true when nothing is left in the spool.
  bool replay_spool() { return writer_.replay(true); }
  // Turns the mission finished (ok, aborted or rejected) while this recorder heard it.
  int turns_finished() const { return turns_finished_; }

 private:
  store::Store& store_;
  StoreWriter writer_;
  int turns_finished_ = 0;
  std::int64_t mission_id_;
  double flush_period_s_;
  std::vector<store::NavRow> pending_;
  CurrentTracker current_;
};

}  // namespace avk::app
