#pragma once
// A mission's navigation as recorded: every report with the guidance input in force.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "store/store_error.hpp"

namespace avk::store {

// One navigation report as the mission records it, with the guidance input in force.
struct NavRow {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
  double speed_mps = 0.0;
  std::optional<double> desired_heading_deg;
  std::optional<double> desired_speed_mps;
  std::string helm_mode;
  friend bool operator==(const NavRow&, const NavRow&) = default;
};

// A navigation row with its rowid: the keyset cursor of page().
struct NavPageRow {
  std::int64_t rowid = 0;
  NavRow row;
};

class NavigationRepository {
 public:
  virtual ~NavigationRepository() = default;

  // One transaction, one prepared statement for the whole batch.
  virtual void append(std::int64_t mission_id, std::span<const NavRow> rows) = 0;
  // In time order, then insertion order.
  virtual std::vector<NavRow> for_mission(std::int64_t mission_id) = 0;
  // The same rows in the same order, one at a time: a long mission's navigation need not be held
  // whole. fn may read through the same Store.
  virtual void for_each(std::int64_t mission_id, const std::function<void(const NavRow&)>& fn) = 0;
  // How many navigation rows the mission holds: what a reader reserves before for_each.
  virtual std::int64_t count(std::int64_t mission_id) = 0;
  // Keyset pagination in insertion (rowid) order: at most `limit` rows with rowid > after_rowid.
  // Insertion order, not time order, so that a page boundary never moves while a mission records.
  virtual std::vector<NavPageRow> page(std::int64_t mission_id, std::int64_t after_rowid,
                                       int limit) = 0;
  // The latest report on the mission clock (of two at one time, the one recorded last): where
  // the vehicle was last seen. None when the mission recorded no navigation.
  virtual std::optional<NavPageRow> last(std::int64_t mission_id) = 0;
};

}  // namespace avk::store
