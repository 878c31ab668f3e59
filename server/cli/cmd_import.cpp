// `avk import alog`: a MOOS-IvP log into the store as a mission of its own (docs/alog-import.md).
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>

#include "app/alog_import.hpp"
#include "app/context.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

constexpr std::size_t kProblemsShown = 5;

std::string counts_text(const app::TurnCounts& c) {
  return std::to_string(c.ok) + " ok, " + std::to_string(c.aborted) + " aborted, " +
         std::to_string(c.rejected) + " rejected";
}

const std::set<std::string> kAlogValues = {
    "db", "vehicle", "names", "turn-record", "threshold", "speed-tolerance", "max-yaw-rate"};

double positive(const Args& a, const std::string& name, double fallback) {
  const double v = a.number(name).value_or(fallback);
  if (!(v > 0.0)) throw UsageError("--" + name + " must be positive");
  return v;
}

int import_alog(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, kAlogValues, {"harvest"});
  if (a.positional().size() != 1) throw UsageError("expected one .alog file");
  const std::string path = a.positional()[0];
  const std::string db_path = a.require("db");
  vehicle::AlogNames names;
  try {
    names = vehicle::parse_alog_names(a.get("names").value_or(""));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--names: ") + e.what());
  }
  if (const auto v = a.get("turn-record")) {
    if (v->empty() || v->find_first_of(" \t") != std::string::npos)
      throw UsageError("--turn-record needs a variable name");
    names.turn_record = *v;
  }
  mission::TurnExtractorOptions options;
  options.completion.threshold_deg = positive(a, "threshold", options.completion.threshold_deg);
  options.condition_set.speed_tolerance_mps =
      positive(a, "speed-tolerance", options.condition_set.speed_tolerance_mps);
  options.condition_set.max_yaw_rate_dps =
      positive(a, "max-yaw-rate", options.condition_set.max_yaw_rate_dps);
  const std::filesystem::path file(path);
  // The use case checks the id (and says so naming --vehicle's field).
  const std::string vehicle_id = a.get("vehicle").value_or(file.stem().string());

  std::error_code ec;
  std::ifstream in;
  if (!std::filesystem::is_directory(file, ec)) in.open(file, std::ios::binary);
  if (!in.is_open() || !in) {
    io.err << "avk import: cannot open '" << path << "': "
           << (std::filesystem::is_directory(file, ec) ? "is a directory" : std::strerror(errno))
           << "\n";
    return 1;
  }

  app::AlogImportRequest request;
  request.source = path;
  request.mission_name = file.filename().string();
  request.vehicle_id = vehicle_id;
  request.names = names;
  request.extraction = options;
  request.harvest = a.flag("harvest");
  app::Context ctx(db_path);
  const app::AlogImportReport import = value_or_fail(app::import_alog(ctx, in, request));
  const std::int64_t mission_id = import.mission_id;

  const auto& rs = import.reader;
  const auto& ns = import.nav;
  const auto& bad = import.malformed;
  io.out << "imported " << path << " as mission " << mission_id << " of vehicle " << vehicle_id
         << "\n";
  io.out << "lines: " << rs.lines << " read (" << rs.bytes << " bytes), " << rs.header_lines
         << " header, " << rs.blank_lines << " blank, " << rs.entries << " postings, " << bad.count
         << " malformed\n";
  for (std::size_t i = 0; i < bad.first.size() && i < kProblemsShown; ++i)
    io.out << "  line " << bad.first[i].line << ": " << bad.first[i].reason << "\n";
  if (bad.count > kProblemsShown) io.out << "  ... and " << bad.count - kProblemsShown << " more\n";
  io.out << "navigation: " << import.nav_stored << " samples stored";
  if (ns.incomplete_groups)
    io.out << ", " << ns.incomplete_groups << " groups without x, y and heading skipped";
  if (ns.max_speed_mps) io.out << "; top speed " << fixed(*ns.max_speed_mps, 2) << " m/s";
  io.out << "\n";
  const app::TurnCounts& rec = import.from_records;
  const app::TurnCounts& ext = import.from_extraction;
  io.out << "turns: " << rec.total() + ext.total() << " stored\n";
  io.out << "  from turn records (" << names.turn_record << "): " << rec.total() << " ("
         << counts_text(rec) << ")\n";
  io.out << "  extracted from desired heading steps: " << ext.total() << " (" << counts_text(ext)
         << ")" << (ns.turn_records ? "; not used: the log has turn records" : "") << "\n";
  if (import.harvest) print_harvest(*import.harvest, io.out);
  io.out << "mission " << mission_id << " done\n";
  return 0;
}

}  // namespace

int cmd_import(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'import alog|mcap FILE --db FILE'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "alog") return import_alog(rest, io);
  if (args[0] == "mcap") return import_mcap(rest, io);
  throw UsageError("unknown subcommand 'import " + args[0] + "'");
}

}  // namespace avk::server
