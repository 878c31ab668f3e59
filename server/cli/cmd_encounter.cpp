// avk encounter run|generate: the encounter test bench (docs/encounter-format.md).
#include <chrono>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "app/context.hpp"
#include "app/encounters.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/files.hpp"
#include "server/cli/sim_options.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

std::string opt_text(const std::optional<double>& v, int decimals, bool sign = false) {
  if (!v) return "-";
  std::ostringstream s;
  if (sign) s << std::showpos;
  s << std::fixed << std::setprecision(decimals) << *v;
  return s.str();
}

std::vector<app::PredictionMethod> methods_from(const Args& a) {
  const std::string m = a.get("method").value_or("all");
  if (m == "all") {
    return {app::PredictionMethod::avk, app::PredictionMethod::model,
            app::PredictionMethod::instantaneous};
  }
  const auto one = app::prediction_method_from_string(m);
  if (!one) throw UsageError("--method must be avk, model, instantaneous or all, got '" + m + "'");
  return {*one};
}

int whole_option(const Args& a, const std::string& name, int fallback, int lo, int hi) {
  const auto v = a.number(name);
  if (!v) return fallback;
  if (*v < lo || *v > hi || std::floor(*v) != *v) {
    throw UsageError("--" + name + " must be a whole number from " + std::to_string(lo) + " to " +
                     std::to_string(hi));
  }
  return static_cast<int>(*v);
}

std::string flags_text(const app::EncounterMethodResult& r) {
  std::string f;
  if (r.violation) f += "VIOLATION ";
  if (r.no_maneuver_while_one_existed) f += "none-while-safe-existed ";
  if (r.unsafe_while_safe_existed) f += "unsafe-while-safe-existed ";
  return f;
}

void print_summary(const app::EncounterBench& b, std::ostream& out) {
  out << "method         scenarios  violations   rate  no-maneuver  none-while-safe  "
         "unsafe-while-safe  mean|dpsi|  cpa-err  |cpa-err|  |along|  |cross|\n";
  for (const auto& m : b.summary) {
    out << std::left << std::setw(15) << app::to_string(m.method) << std::right;
    if (!m.available) {
      out << "not available: " << m.note << "\n";
      continue;
    }
    out << std::setw(9) << m.scenarios << std::setw(12) << m.violations << std::setw(7)
        << fixed(m.violation_rate, 3) << std::setw(13) << m.no_maneuver << std::setw(17)
        << m.no_maneuver_while_one_existed << std::setw(19) << m.unsafe_while_safe_existed
        << std::setw(12) << opt_text(m.mean_abs_dheading_deg, 1) << std::setw(9)
        << opt_text(m.mean_cpa_error_m, 2, true) << std::setw(11)
        << opt_text(m.mean_abs_cpa_error_m, 2) << std::setw(9)
        << opt_text(m.mean_abs_along_error_m, 2) << std::setw(9)
        << opt_text(m.mean_abs_cross_error_m, 2) << "\n";
  }
  // Is a predicted risk of p violated a share p of the time? Every flown candidate counts.
  for (const auto& m : b.summary) {
    if (!m.available || m.calibration.empty()) continue;
    out << "\nrisk calibration, " << app::to_string(m.method)
        << " (every flown candidate)\n  predicted risk   candidates  mean predicted  observed\n";
    for (const auto& bin : m.calibration) {
      if (bin.candidates == 0) continue;
      out << "  [" << fixed(bin.lo, 2) << ", " << fixed(bin.hi, 2) << ")" << std::setw(13)
          << bin.candidates << std::setw(16) << fixed(bin.mean_predicted, 3) << std::setw(10)
          << fixed(bin.observed_rate, 3) << "\n";
    }
  }
}

void print_table(const app::EncounterBench& b, Io& io) {
  io.out << "scenario                              standoff  held  safe  method          dpsi  "
            "pred-cpa  edge-cpa  actual  flags\n";
  for (const auto& s : b.scenarios) {
    for (const auto& r : s.methods) {
      io.out << std::left << std::setw(38) << s.name << std::right << std::setw(8)
             << fixed(s.standoff_m, 1) << std::setw(6) << fixed(s.course_held_cpa_m, 1)
             << std::setw(6) << (s.safe_existed ? "yes" : "no") << "  " << std::left
             << std::setw(14) << app::to_string(r.method) << std::right << std::setw(6)
             << opt_text(r.chosen_dheading_deg, 0, true) << std::setw(10)
             << opt_text(r.predicted_cpa_m, 1) << std::setw(10)
             << opt_text(r.predicted_edge_cpa_m, 1) << std::setw(8) << fixed(r.actual_cpa_m, 1)
             << "  " << flags_text(r) << "\n";
    }
  }
  io.out << "\n";
  print_summary(b, io.out);
  // Where the methods chose differently: what each chose and what it got.
  bool header = false;
  for (const auto& s : b.scenarios) {
    bool differ = false;
    for (const auto& r : s.methods)
      differ = differ || r.chosen_dheading_deg != s.methods.front().chosen_dheading_deg;
    if (!differ) continue;
    if (!header) io.out << "\nscenarios where the methods disagree (dpsi deg -> actual CPA m)\n";
    header = true;
    io.out << "  " << std::left << std::setw(38) << s.name << std::right;
    for (const auto& r : s.methods) {
      io.out << "  " << app::to_string(r.method) << " " << opt_text(r.chosen_dheading_deg, 0, true)
             << " -> " << fixed(r.actual_cpa_m, 1) << (r.violation ? "!" : "");
    }
    io.out << "\n";
  }
}

int encounter_run(const std::vector<std::string>& rest, Io& io) {
  const Args a(
      rest,
      {"scenarios", "db", "vehicle-id", "vehicle", "sim-config", "method", "seed", "ticks",
       "format", "step", "threads", "current", "sea-seeds", "max-risk", "rule", "speed-reference"},
      {"jitter", "colregs", "ray-band"});
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "json" && format != "csv")
    throw UsageError("--format must be table, json or csv");
  const std::string scenarios_path = a.require("scenarios");
  app::Context ctx(a.require("db"));
  app::EncounterBenchQuery q;
  q.setup = sim_setup_from(a, io, "catamaran:m200");
  q.seed = q.setup.scheduler.seed;
  q.methods = methods_from(a);
  q.candidate_step_deg = a.number("step").value_or(5.0);
  if (!(q.candidate_step_deg > 0.0 && q.candidate_step_deg <= 180.0))
    throw UsageError("--step must be in (0, 180] degrees");
  q.threads = whole_option(a, "threads", 2, 1, 64);
  const std::string current = a.get("current").value_or("estimated");
  if (current != "estimated" && current != "none")
    throw UsageError("--current must be estimated or none");
  q.use_estimated_current = current == "estimated";
  if (const auto seeds = a.get("sea-seeds")) {
    std::stringstream list(*seeds);
    for (std::string item; std::getline(list, item, ',');) {
      const auto v = nlohmann::json::parse(item, nullptr, false);
      if (!v.is_number_unsigned()) throw UsageError("--sea-seeds needs whole numbers, e.g. 1,2");
      q.sea_seeds.push_back(v.get<std::uint64_t>());
    }
    if (q.sea_seeds.empty()) throw UsageError("--sea-seeds needs at least one seed");
  }
  q.max_risk = a.number("max-risk").value_or(q.max_risk);
  if (!(q.max_risk >= 0.0 && q.max_risk <= 1.0)) throw UsageError("--max-risk must be in [0, 1]");
  const std::string rule = a.get("rule").value_or("risk");
  if (rule != "risk" && rule != "corridor") throw UsageError("--rule must be risk or corridor");
  q.corridor_rule = rule == "corridor";
  q.prefer_starboard = a.flag("colregs");
  q.ray_band = a.flag("ray-band");
  q.speed_over_ground = speed_reference_option(a);
  q.vehicle_id = vehicle_of(a, ctx, {}, "vehicle-id");
  const app::EncounterFile file =
      value_or_fail(app::parse_encounter_file(read_file(scenarios_path, io.in)));
  const auto started = std::chrono::steady_clock::now();
  const app::EncounterBench bench = value_or_fail(app::run_encounter_bench(ctx, file, q));
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
  if (format == "json") {
    io.out << encounter_bench_json(bench, q).dump(2) << "\n";
  } else if (format == "csv") {
    io.out << encounter_bench_csv(bench);
  } else {
    print_table(bench, io);
  }
  if (format != "table") print_summary(bench, io.err);
  for (const auto& m : bench.summary) {
    if (!m.available)
      io.err << "encounter run: method " << app::to_string(m.method) << " skipped: " << m.note
             << "\n";
  }
  io.err << "encounter run: " << file.scenarios.size() << " scenarios, " << bench.flights
         << " maneuvers flown on " << q.threads << " thread(s) in " << fixed(took.count(), 1)
         << " s (vehicle " << q.vehicle_id << ", plant " << vehicle::to_string(q.setup.vehicle.kind)
         << ", seed " << q.seed << ", current "
         << (bench.current ? water_current_json(bench.current, "estimated").dump() : "none")
         << ")\n";
  return 0;
}

int encounter_generate(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"seed", "count"});
  const auto seed = a.number("seed").value_or(1.0);
  if (seed < 0 || std::floor(seed) != seed) throw UsageError("--seed needs a whole number >= 0");
  const int count = whole_option(a, "count", 60, 1, 100000);
  const app::EncounterFile f =
      value_or_fail(app::generate_encounters(static_cast<std::uint64_t>(seed), count));
  io.out << app::encounter_file_json(f);
  return 0;
}

}  // namespace

int cmd_encounter(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'encounter run' or 'encounter generate'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "run") return encounter_run(rest, io);
  if (args[0] == "generate") return encounter_generate(rest, io);
  throw UsageError("unknown subcommand 'encounter " + args[0] + "'");
}

}  // namespace avk::server
