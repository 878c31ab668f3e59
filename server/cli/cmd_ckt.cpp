#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/predict.hpp"
#include "app/utc_time.hpp"
#include "app/yaw_rate_table.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/ckt3_file.hpp"
#include "kinematics/ckt_file.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/files.hpp"
#include "server/cli/turn_file.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace kin = avk::kinematics;

namespace {

enum class OutFormat { json, csv };

OutFormat out_format(const Args& a) {
  const std::string f = a.get("format").value_or("json");
  if (f == "json") return OutFormat::json;
  if (f == "csv") return OutFormat::csv;
  throw UsageError("--format must be json or csv, got '" + f + "'");
}

void emit(const Args& a, Io& io, const std::string& content) {
  if (const auto out = a.get("out"); out && *out != "-") {
    write_file_atomic(*out, content);
  } else {
    io.out << content;
  }
}

kin::CktOptions build_options(const Args& a) {
  kin::CktOptions options;
  if (const auto fit = a.get("fit")) {
    const auto kind = kin::fit_kind_from_string(*fit);
    if (!kind) throw UsageError("--fit must be arc_length_spline or poly4_xy, got '" + *fit + "'");
    options.fit_kind = *kind;
  }
  if (const auto eps = a.number("epsilon")) {
    if (!(*eps > 0.0)) throw UsageError("--epsilon must be positive (metres)");
    options.pwl_epsilon_m = *eps;
  }
  return options;
}

// From a turn file, or from the database, where the table is kept as a snapshot.
app::BuiltTable build_table(const Args& a, Io& io) {
  if (a.get("turns").has_value() == a.get("db").has_value())
    throw UsageError("give exactly one source: --turns FILE or --db FILE");
  app::BuiltTable out;
  if (const auto path = a.get("turns")) {
    if (!a.all("mission").empty()) throw UsageError("--mission goes with --db");
    if (a.flag("include-harvested")) throw UsageError("--include-harvested goes with --db");
    const auto records = parse_turn_file(read_file(*path, io.in), *path == "-" ? "stdin" : *path);
    std::vector<kin::TurnSequence> turns;
    turns.reserve(records.size());
    for (const auto& r : records)
      turns.push_back(r.turn);
    out.table = kin::Ckt::build(turns, build_options(a), std::nullopt, &out.report);
    out.table.vehicle_id =
        a.get("vehicle").value_or(turns.empty() ? "" : turns.front().meta().vehicle_id);
    out.table.vehicle_length_m = a.number("vehicle-length");
    out.table.created_utc = app::utc_now_iso8601();
  } else {
    app::Context ctx(*a.get("db"));
    const auto missions = mission_ids(a);
    const std::string vehicle = vehicle_of(a, ctx, missions);
    out = value_or_fail(app::build_ckt(ctx, vehicle, missions, build_options(a),
                                       a.number("vehicle-length"), a.flag("include-harvested")));
  }
  const auto& report = out.report;
  io.err << "ckt: " << report.turns_used << " turns used, " << report.turns_skipped_status
         << " aborted/rejected skipped, " << report.turns_unassigned << " off the grid, "
         << report.turns_speed_change << " with a speed change (not in constant-speed cells)\n";
  if (a.flag("include-harvested"))
    io.err << "ckt: " << out.harvested_turns << " of the turns harvested from navigation logs\n";
  return out;
}

kin::Ckt load_ckt(const std::string& path, Io& io) {
  const std::string text = read_file(path, io.in);
  try {
    return kin::parse_ckt_json(text);
  } catch (const std::exception& e) {
    throw std::runtime_error((path == "-" ? std::string("stdin") : path) + ": " + e.what());
  }
}

std::string serialise(const kin::Ckt& table, OutFormat f) {
  return f == OutFormat::json ? kin::ckt_to_json_string(table) : kin::ckt_to_csv(table);
}

int summarise(const kin::Ckt& t, Io& io) {
  std::size_t cells = 0, turns = 0;
  for (const auto& c : t.cells()) {
    if (!c.has_data()) continue;
    ++cells;
    turns += c.n_turns;
  }
  io.err << "ckt: vehicle '" << t.vehicle_id << "', schema " << kin::kCktSchemaVersion << ", "
         << t.grid().speeds_mps.size() << " speeds x " << t.grid().dheadings_deg.size()
         << " heading changes, " << cells << " cells with turns, " << turns << " turns";
  if (const auto r = t.speed_range_mps()) {
    io.err << ", speeds " << r->first << "-" << r->second << " m/s";
  }
  io.err << "\n";
  return 0;
}

int query(const Args& a, Io& io) {
  const std::string ckt_path = a.require("ckt");
  const auto speed = a.number("speed");
  const auto dheading = a.number("dheading");
  if (!speed) throw UsageError("missing required option --speed (m/s)");
  if (!dheading) throw UsageError("missing required option --dheading (deg, + right, - left)");
  const auto x = a.number("x"), y = a.number("y"), heading = a.number("heading");
  const bool placed = x || y || heading;
  if (placed && !(x && y && heading)) {
    throw UsageError("a pose needs all of --x, --y and --heading");
  }
  const OutFormat format = out_format(a);
  const kin::Ckt table = load_ckt(ckt_path, io);
  app::PredictQuery q;
  q.vehicle_id = table.vehicle_id;
  q.speed_mps = *speed;
  q.dheading_deg = *dheading;
  if (placed) q.pose = kin::Pose{*x, *y, *heading};
  q.current = current_option(a, false).current;
  q.speed_over_ground = speed_reference_option(a);
  const app::Prediction p = value_or_fail(app::predict_with_table(table, q));
  emit(a, io,
       format == OutFormat::csv ? trajectory_csv(p.trajectory) : prediction_json(p).dump() + "\n");
  return 0;
}

// `avk ckt yaw-rate`: the vehicle's table over initial yaw rate as a schema-4 CKT file, with its
// coverage and (with a model) the model's path error where cells were measured, on stderr.
int yaw_rate(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "model", "out"}, {"no-model"}, {"yaw-rate"});
  app::Context ctx(a.require("db"));
  app::YawRateTableOptions o;
  for (const std::string& v : a.all("yaw-rate")) {
    try {
      std::size_t used = 0;
      const double r = std::stod(v, &used);
      if (used != v.size() || !std::isfinite(r)) throw std::invalid_argument(v);
      if (!o.yaw_rates_dps) o.yaw_rates_dps.emplace();
      o.yaw_rates_dps->push_back(r);
    } catch (const std::exception&) {
      throw UsageError("--yaw-rate expects a number (deg/s, + into the turn), got '" + v + "'");
    }
  }
  o.fill_with_model = !a.flag("no-model");
  o.model_id = model_option(a);
  o.check_model = o.fill_with_model;
  const std::string vehicle = vehicle_of(a, ctx, {});
  const app::YawRateTable t = value_or_fail(app::vehicle_yaw_rate_table(ctx, vehicle, o));
  kin::YawRateCkt table = t.table;
  emit(a, io, kin::yaw_rate_ckt_to_json_string(table));
  io.err << "ckt: vehicle '" << vehicle << "', " << table.slices().size()
         << " initial yaw rate slices";
  if (t.model_id) io.err << ", empty cells filled by model " << *t.model_id;
  io.err << "\n";
  for (const auto& c : t.coverage) {
    io.err << "  slice " << c.initial_yaw_rate_dps << " deg/s: " << c.measured << " measured, "
           << c.model << " model, " << c.empty << " empty\n";
  }
  for (const auto& c : t.model_checks) {
    io.err << "  cell " << c.speed_mps << " m/s " << c.dheading_deg << " deg "
           << c.initial_yaw_rate_dps << " deg/s (" << c.n_turns << " turns): model path error "
           << c.model_error_m << " m, table " << c.table_error_m << " m\n";
  }
  return 0;
}

}  // namespace

int cmd_ckt(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'ckt build|export|import|query|yaw-rate'");
  const std::string sub = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (sub == "yaw-rate") return yaw_rate(rest, io);
  const std::set<std::string> build_values = {
      "turns", "db", "out", "format", "vehicle", "vehicle-length", "fit", "epsilon"};
  if (sub == "build") {
    const Args a(rest, build_values, {"include-harvested"}, {"mission"});
    const OutFormat format = out_format(a);
    const app::BuiltTable t = build_table(a, io);
    emit(a, io, serialise(t.table, format));
    if (t.snapshot_id) io.err << "ckt: saved as snapshot " << t.snapshot_id << "\n";
    return summarise(t.table, io);
  }
  if (sub == "export") {
    std::set<std::string> values = build_values;
    values.insert("ckt");
    const Args a(rest, values, {"include-harvested"}, {"mission"});
    const OutFormat format = out_format(a);
    kin::Ckt t;
    if (const auto ckt = a.get("ckt")) {
      if (a.get("turns") || a.get("db"))
        throw UsageError("give one source: --turns FILE, --db FILE or --ckt FILE");
      t = load_ckt(*ckt, io);
    } else {
      t = build_table(a, io).table;
    }
    emit(a, io, serialise(t, format));
    return 0;
  }
  if (sub == "import") {
    const Args a(rest, {"out", "format"});
    if (a.positional().size() != 1) throw UsageError("expected one CKT file to import");
    const kin::Ckt t = load_ckt(a.positional()[0], io);
    if (a.get("out")) emit(a, io, serialise(t, out_format(a)));
    return summarise(t, io);
  }
  if (sub == "query") {
    return query(Args(rest, {"ckt", "speed", "dheading", "x", "y", "heading", "format", "out",
                             "current", "speed-reference"}),
                 io);
  }
  throw UsageError("unknown subcommand 'ckt " + sub + "'");
}

}  // namespace avk::server
