#pragma once
// Which station this process is, as recorded with the missions it runs: several stations may
// share one PostgreSQL database, and only the station that ran a mission can tell whether its
// process is still alive.

#include <optional>
#include <string>

namespace avk::app {

// The host name unless set (avk serve --station-id).
std::string station_id();
// Before any Context opens the database.
void set_station_id(std::string id);

// Why `id` cannot name a station (empty, longer than 64 characters, or other than letters,
// digits, '.', '_' and '-'); none when it can.
std::optional<std::string> station_id_problem(const std::string& id);

// True when `db` names a database server (PostgreSQL) rather than an SQLite file.
bool is_database_server(const std::string& db);

}  // namespace avk::app
