#pragma once
// Saved CKT tables: the document as written, and the missions it was built from.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "store/store_error.hpp"

namespace avk::store {

struct CktSnapshot {
  std::int64_t id = 0;
  std::string created_utc;
  std::vector<std::int64_t> mission_ids;
  std::string document;  // the CKT file (docs/ckt-format.md) as saved
  kinematics::Ckt table;
};

class CktSnapshotRepository {
 public:
  virtual ~CktSnapshotRepository() = default;

  virtual std::int64_t save(const kinematics::Ckt& table,
                            const std::vector<std::int64_t>& mission_ids) = 0;
  // The newest snapshot of the vehicle's table. Throws StoreError when its stored document no
  // longer parses.
  virtual std::optional<CktSnapshot> latest(const std::string& vehicle_id) = 0;
  // Its id alone (0: none), without reading the document: tells a cache whether it changed.
  virtual std::int64_t latest_id(const std::string& vehicle_id) = 0;
};

}  // namespace avk::store
