#include "server/cli/station_options.hpp"

#include "app/station_identity.hpp"
#include "app/store_link.hpp"

namespace avk::server {

void apply_station_options(const Args& a) {
  if (const auto id = a.get("station-id")) {
    if (const auto why = app::station_id_problem(*id)) throw UsageError("--station-id " + *why);
    app::set_station_id(*id);
  }
  if (const auto spool = a.get("spool")) {
    if (spool->empty()) throw UsageError("--spool needs a file");
    app::set_spool_path(*spool);
  }
}

}  // namespace avk::server
