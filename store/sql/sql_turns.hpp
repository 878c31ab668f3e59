#pragma once
// TurnRepository on either engine: the turns table, each turn's summary columns beside its
// documents.

#include <functional>
#include <string_view>

#include "store/database.hpp"
#include "store/sql/packed_turns.hpp"
#include "store/turns.hpp"

namespace avk::store::sql {

// The row's columns as given (row.id and row.mission_id aside), inside the caller's transaction;
// the new turn id.
std::int64_t insert_turn(Database& db, std::int64_t mission_id, const TurnRow& r,
                         const TurnDocuments& d);

class SqlTurns final : public TurnRepository {
 public:
  explicit SqlTurns(Database& db) : db_(db) {}

  std::int64_t add(std::int64_t mission_id, const kinematics::TurnSequence& raw,
                   kinematics::TurnStatus status, const std::string& reason, const TurnStart& start,
                   const std::string& record_key) override;
  std::int64_t newest_ok_id(const std::string& vehicle_id, bool include_harvested) override;
  std::vector<TurnRow> list(const TurnFilter& filter) override;
  std::optional<TurnRow> get_row(std::int64_t turn_id) override;
  std::optional<StoredTurn> get(std::int64_t turn_id) override;
  std::vector<kinematics::TurnSequence> load_normalized(
      const std::vector<std::int64_t>& mission_ids, const std::optional<std::string>& vehicle_id,
      bool include_harvested, TurnFrameChoice frame, const TurnsLeftOut& left_out) override;
  std::vector<double> start_times(std::int64_t mission_id) override;

  // Runs inside add's transaction after each step ("turn_inserted"): a test seam.
  void set_hook(std::function<void(std::string_view step)> hook) { hook_ = std::move(hook); }

 private:
  Database& db_;
  std::function<void(std::string_view)> hook_;
};

}  // namespace avk::store::sql
