// `avk db copy --from DB --to DB`: a station's data moved between an SQLite file and a
// PostgreSQL database, either way (docs/postgresql.md).
#include <iomanip>
#include <ostream>

#include "app/db_copy.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"

namespace avk::server {

int cmd_db(const std::vector<std::string>& args, Io& io) {
  if (args.empty() || args[0] != "copy")
    throw UsageError("expected 'db copy --from FILE_OR_URL --to FILE_OR_URL'");
  const Args a(std::vector<std::string>(args.begin() + 1, args.end()), {"from", "to"}, {});
  const auto copied = value_or_fail(app::copy_database(a.require("from"), a.require("to")));
  std::int64_t total = 0;
  for (const auto& t : copied) {
    io.out << std::left << std::setw(18) << t.table << t.rows << "\n";
    total += t.rows;
  }
  io.out << "copied " << total << " rows; every table's count matches the source\n";
  return 0;
}

}  // namespace avk::server
