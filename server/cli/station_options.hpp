#pragma once
// The options that say which station this process is and where it spools: --station-id NAME
// (recorded with its missions; default the host name) and --spool FILE (where writes wait while
// a PostgreSQL database is away; default "<station id>.spool.db" in the working directory).

#include "server/cli/args.hpp"

namespace avk::server {

// Applies them for this process; UsageError for a station id that cannot name one.
void apply_station_options(const Args& a);

}  // namespace avk::server
