#pragma once
// MissionRepository on either engine: the missions, condition_sets and mission_events tables, and
// the summaries of a mission read over its turns and navigation.

#include <string>
#include <utility>

#include "store/database.hpp"
#include "store/missions.hpp"

namespace avk::store::sql {

class SqlMissions final : public MissionRepository {
 public:
  explicit SqlMissions(Database& db) : db_(db) {}
  // The station recorded with each mission create() makes; empty: none (NULL).
  void set_station_id(std::string station_id) { station_id_ = std::move(station_id); }

  std::int64_t create(const std::string& vehicle_id, const std::string& name,
                      const std::string& config_json) override;
  void set_status(std::int64_t mission_id, MissionStatus status, const std::string& reason,
                  double t_s) override;
  std::optional<Mission> get(std::int64_t mission_id) override;
  std::vector<Mission> list() override;
  void set_runner(std::int64_t mission_id, std::optional<std::int64_t> pid) override;
  void close_orphaned(std::int64_t mission_id, const std::string& reason,
                      std::optional<double> end_s) override;

  void append_condition_set(std::int64_t mission_id, const ConditionSetTiming& timing) override;
  std::vector<ConditionSetTiming> condition_sets(std::int64_t mission_id) override;

  std::int64_t append_event(std::int64_t mission_id, double t_s, const std::string& kind,
                            const std::string& message) override;
  std::vector<MissionEvent> events(std::int64_t mission_id, std::int64_t after_id,
                                   int limit) override;

  std::optional<double> clock_end_s(std::int64_t mission_id) override;
  double station_clock_end_s() override;
  std::vector<CellStats> cell_stats(std::int64_t mission_id) override;
  std::map<std::int64_t, TurnCounts> turn_counts() override;

  // The mission's row as given (id and runner_pid aside, created_utc kept); the new id.
  static std::int64_t insert(Database& db, const Mission& m);

 private:
  // Throws StoreError when the last statement changed no mission.
  void expect_changed(std::int64_t mission_id) const;

  Database& db_;
  std::string station_id_;
};

}  // namespace avk::store::sql
