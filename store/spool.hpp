#pragma once
// The local file a station writes to while its database server cannot be reached: each write it
// could not make, in the order it was to be made, kept until it is replayed. An SQLite file of
// its own (not the station's schema), durable at every write (synchronous FULL): a write that
// reached the spool survives a crash of the station too.

#include <cstdint>
#include <optional>
#include <string>

#include "store/sqlite.hpp"

namespace avk::store {

struct SpooledWrite {
  std::int64_t seq = 0;  // the order of the writes
  std::string kind;      // what to write ("nav", "turn", "event", ...): the writer's vocabulary
  std::int64_t mission_id = 0;
  std::string payload;  // the write's data, as the writer encoded it
};

class Spool {
 public:
  // Opens (creating if needed) the spool file. Throws StoreError.
  explicit Spool(const std::string& path);

  // Appends a write; its seq.
  std::int64_t push(const std::string& kind, std::int64_t mission_id, const std::string& payload);
  // The oldest write still spooled, if any.
  std::optional<SpooledWrite> oldest();
  // Removes a replayed write.
  void remove(std::int64_t seq);
  std::int64_t count();
  bool integrity_check();  // PRAGMA integrity_check says "ok"

 private:
  Connection db_;
};

}  // namespace avk::store
