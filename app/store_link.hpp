#pragma once
// Whether the station can write to its database, and the local spool that keeps its writes while
// it cannot: a mission goes on when the PostgreSQL server goes away, its writes go to the spool
// in order, and they are replayed in the same order when the server is back
// (app/store_writer.hpp). An SQLite station has no spool: its file is local, and a failure to
// write it is an error as before.

#include <cstdint>
#include <string>

namespace avk::app {

// The station's store link as /health and the dashboard show it.
struct StoreLinkView {
  std::string engine;  // "sqlite" or "postgresql"
  bool spooling = false;
  std::int64_t spooled = 0;  // writes waiting in the spool
  std::string spool_path;    // empty: no spool (SQLite)
  std::string last_error;    // why the last write went to the spool
};
StoreLinkView store_link_view(const std::string& db);

// Where this station spools (default: "<station id>.spool.db" in the working directory); set
// before any mission runs.
void set_spool_path(std::string path);
std::string spool_path();

}  // namespace avk::app
