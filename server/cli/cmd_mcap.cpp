// `avk mission export ID --format mcap` and `avk import mcap FILE`: a mission as an MCAP recording
// and back (app/mission_mcap.hpp, docs/foxglove.md).
#include <ostream>
#include <set>

#include "app/context.hpp"
#include "app/mission_mcap.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/files.hpp"
#include "server/cli/m200_options.hpp"

namespace avk::server {

namespace {

void print_counts(const app::McapChannelCounts& c, std::ostream& out) {
  for (const auto& [topic, n] : c.per_topic)
    out << "  " << topic << ": " << n << "\n";
}

app::mcap::Compression compression_from(const Args& a) {
  const std::string c = a.get("compression").value_or("zstd");
  if (c == "zstd") return app::mcap::Compression::zstd;
  if (c == "none") return app::mcap::Compression::none;
  throw UsageError("--compression must be zstd or none, not '" + c + "'");
}

}  // namespace

int mission_export(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "format", "out", "compression", "datum"});
  if (a.positional().size() != 1) throw UsageError("expected one mission id");
  const std::int64_t id = parse_id(a.positional()[0], "the mission id");
  const std::string format = a.get("format").value_or("mcap");
  if (format != "mcap") throw UsageError("--format must be mcap, not '" + format + "'");
  const std::string out_path = a.require("out");
  app::McapExportOptions options;
  options.compression = compression_from(a);
  options.datum = datum_from(a);
  app::Context ctx(a.require("db"));
  const app::McapExport e = value_or_fail(app::export_mission_mcap(ctx, id, options));
  write_file_atomic(out_path, e.bytes);
  io.out << "wrote mission " << id << " to " << out_path << ": " << e.bytes.size() << " bytes ("
         << app::mcap::to_string(options.compression)
         << (options.compression == app::mcap::Compression::none ? "uncompressed" : "") << "), "
         << e.messages.total() << " messages\n";
  print_counts(e.messages, io.out);
  return 0;
}

int import_mcap(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db"});
  if (a.positional().size() != 1) throw UsageError("expected one .mcap file");
  const std::string path = a.positional()[0];
  const std::string bytes = read_file(path, io.in);
  app::Context ctx(a.require("db"));
  const app::McapImport r = value_or_fail(app::import_mission_mcap(ctx, bytes));
  io.out << "imported " << path << " (mission " << r.source_mission_id << " of vehicle "
         << r.vehicle_id << ") as mission " << r.mission_id << "\n"
         << "stored: " << r.nav_samples << " navigation samples, " << r.turns << " turns, "
         << r.events << " events, " << r.condition_sets << " condition sets"
         << (r.current ? ", the current estimate" : "") << "\n"
         << "read: " << r.messages.total() << " messages\n";
  print_counts(r.messages, io.out);
  return 0;
}

}  // namespace avk::server
