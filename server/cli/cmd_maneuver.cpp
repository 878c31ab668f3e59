// avk maneuver evaluate|ongoing|fly: the maneuver evaluation guidance asks for, from
// the command line. `evaluate` and `fly` write their options as the body of POST
// .../maneuvers/evaluate and .../maneuvers/simulate and read it with the same reader, so the two
// front ends take the same questions and answer with the same document (--format json). `fly`
// flies one candidate exactly as the encounter bench does (same setup, same seed).
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "app/context.hpp"
#include "app/maneuvers.hpp"
#include "kinematics/angles.hpp"
#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/sim_options.hpp"
#include "server/maneuver_requests.hpp"
#include "server/serialize.hpp"

namespace avk::server {

namespace {

using nlohmann::json;

std::string format_option(const Args& a) {
  const std::string format = a.get("format").value_or("table");
  if (format != "table" && format != "json") throw UsageError("--format must be table or json");
  return format;
}

// "+35", "-10", "0".
std::string signed_deg(double d) {
  std::string text = d > 0.0 ? "+" : "";
  text += fixed(d, 0);
  return text;
}

// --contact x,y,course,speed (repeatable) as the body's contacts.
json contacts_body(const Args& a) {
  json contacts = json::array();
  for (const auto& c : a.number_lists("contact", 4, "x,y,course,speed"))
    contacts.push_back({{"x_m", c[0]}, {"y_m", c[1]}, {"course_deg", c[2]}, {"speed_mps", c[3]}});
  if (contacts.empty()) throw UsageError("give at least one --contact x,y,course,speed");
  return contacts;
}

// The options as the evaluate endpoint's body.
json evaluate_body(const Args& a) {
  const auto own = a.number_list("own", 4, "x,y,heading,speed");
  if (!own) throw UsageError("--own x,y,heading,speed is required");
  json body = {{"own",
                {{"x_m", (*own)[0]},
                 {"y_m", (*own)[1]},
                 {"heading_deg", (*own)[2]},
                 {"speed_mps", (*own)[3]}}},
               {"contacts", json::array()}};
  body["contacts"] = contacts_body(a);
  const std::pair<const char*, const char*> numbers[] = {{"standoff", "standoff_m"},
                                                         {"horizon", "horizon_s"},
                                                         {"step", "candidate_step_deg"},
                                                         {"speed", "candidate_speed_mps"},
                                                         {"corridor", "corridor"}};
  for (const auto& [option, field] : numbers)
    if (const auto v = a.number(option)) body[field] = *v;
  if (const auto m = a.get("method")) body["method"] = *m;
  if (const auto id = model_option(a)) body["model_id"] = *id;
  if (a.flag("no-corridor")) body["use_corridor"] = false;
  const CurrentOption current = current_option(a);
  if (current.live) body["current"] = "live";
  if (current.none) body["current"] = "none";
  if (current.current)
    body["current"] = {{"east_mps", current.current->east_mps},
                       {"north_mps", current.current->north_mps}};
  if (const auto v = a.number("max-risk")) body["max_risk"] = *v;
  if (a.flag("colregs")) body["colregs"] = true;
  if (const auto r = a.get("rule")) body["rule"] = *r;
  if (const auto r = a.get("speed-reference")) body["speed_reference"] = *r;
  return body;
}

void print_evaluation(const app::ManeuverEvaluation& e, std::ostream& out) {
  const app::ManeuverQuery& q = e.query;
  out << "vehicle " << q.vehicle_id << " · method " << app::to_string(q.method);
  if (e.table_source)
    out << " (table from " << *e.table_source << (e.timed_by_turns ? ", timed by its turns" : "")
        << ")";
  if (e.model_id) out << " (model " << *e.model_id << ")";
  out << " · " << q.contacts.size() << " contact" << (q.contacts.size() == 1 ? "" : "s")
      << " · standoff " << fixed(q.standoff_m, 1) << " m · horizon " << fixed(q.horizon_s, 0)
      << " s\n";
  // Plain ASCII in the columns: setw counts bytes.
  out << "frame " << e.frame << " · current ";
  if (e.current)
    out << fixed(std::hypot(e.current->east_mps, e.current->north_mps), 2) << " m/s toward "
        << fixed(kinematics::heading_of_deg(e.current->east_mps, e.current->north_mps), 0) << "°";
  else
    out << "none";
  out << " (" << e.current_source.value_or("none") << ") · speed held "
      << (e.motion.speed_over_ground ? "over ground" : "through the water") << " ("
      << e.motion.speed_reference_source << ")\n";
  out << std::setw(7) << "dpsi" << std::setw(13) << "min CPA (m)" << std::setw(14) << "edge CPA (m)"
      << std::setw(8) << "clears" << std::setw(9) << "risk"
      << "\n";
  for (std::size_t i = 0; i < e.candidates.size(); ++i) {
    const auto& c = e.candidates[i];
    out << std::setw(7) << signed_deg(c.dheading_deg) << std::setw(13) << fixed(c.min_cpa_m, 1)
        << std::setw(14) << (c.min_edge_cpa_m ? fixed(*c.min_edge_cpa_m, 1) : std::string("–"))
        << std::setw(8) << (c.clears ? "yes" : "no") << std::setw(9) << fixed(c.risk, 3)
        << (e.chosen == i ? "   <- chosen" : "") << "\n";
  }
  if (!e.chosen) {
    out << "chosen: none\n";
    return;
  }
  const auto& c = e.candidates[*e.chosen];
  out << "chosen: " << signed_deg(c.dheading_deg) << "° (CPA " << fixed(c.min_cpa_m, 1) << " m";
  if (c.min_edge_cpa_m) out << ", edge " << fixed(*c.min_edge_cpa_m, 1) << " m";
  out << ", risk " << fixed(c.risk, 3) << ", margin " << fixed(e.choice.margin_m, 1)
      << " m): " << e.choice.explanation << "\n";
}

int evaluate(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest,
               {"db", "vehicle", "own", "standoff", "horizon", "method", "model", "step", "speed",
                "corridor", "format", "current", "max-risk", "rule", "speed-reference"},
               {"no-corridor", "colregs"}, {"contact"});
  const std::string format = format_option(a);
  const json body = evaluate_body(a);
  app::Context ctx(a.require("db"));
  const ManeuverRequest request = value_or_fail(maneuver_request(body, vehicle_of(a, ctx, {})));
  const app::ManeuverEvaluation e = value_or_fail(app::evaluate_maneuvers(ctx, request.query));
  if (format == "json")
    io.out << maneuver_evaluation_text(e, request.path_step_s) << "\n";
  else
    print_evaluation(e, io.out);
  return 0;
}

void print_ongoing(const app::OngoingManeuver& o, std::ostream& out) {
  const kinematics::OngoingEvaluation& e = o.evaluation;
  out << "expected after " << fixed(e.elapsed_s, 1) << " s: x " << fixed(e.expected.x_m, 2)
      << " m, y " << fixed(e.expected.y_m, 2) << " m";
  if (e.half_width_m) out << " (corridor half width " << fixed(*e.half_width_m, 2) << " m)";
  out << "\n";
  if (e.deviation_m) {
    out << "deviation " << fixed(*e.deviation_m, 2) << " m";
    if (e.cross_track_m) out << ", cross-track " << fixed(*e.cross_track_m, 2) << " m";
    if (e.inside_corridor)
      out << " (" << (*e.inside_corridor ? "inside" : "outside") << " the "
          << fixed(o.query.corridor_share * 100.0, 0) << " % corridor)";
    out << "\n";
  }
  out << "remaining: " << e.remaining.size() << " points to t = "
      << (e.remaining.empty() ? std::string("–") : fixed(e.remaining.back().t_s, 1)) << " s\n";
}

int ongoing(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest, {"db", "vehicle", "start", "dheading", "speed", "elapsed", "measured",
                      "method", "model", "corridor", "horizon", "format", "current"});
  const std::string format = format_option(a);
  app::OngoingQuery q;
  const auto start = a.number_list("start", 3, "x,y,heading");
  if (!start) throw UsageError("--start x,y,heading is required");
  q.start = {(*start)[0], (*start)[1], (*start)[2]};
  const auto required = [&a](const char* name, const char* what) {
    const auto v = a.number(name);
    if (!v) throw UsageError(std::string("--") + name + " (" + what + ") is required");
    return *v;
  };
  q.dheading_deg = required("dheading", "deg, + starboard");
  q.speed_mps = required("speed", "m/s");
  q.elapsed_s = required("elapsed", "s since the maneuver was commanded");
  if (const auto m = a.number_list("measured", 2, "x,y"))
    q.measured = kinematics::Point{(*m)[0], (*m)[1]};
  q.method = method_option(a);
  q.model_id = model_option(a);
  q.corridor_share = a.number("corridor").value_or(q.corridor_share);
  q.horizon_s = a.number("horizon").value_or(q.horizon_s);
  const CurrentOption current = current_option(a);
  q.current = current.current;
  q.live_current = current.live;
  q.no_current = current.none;
  app::Context ctx(a.require("db"));
  q.vehicle_id = vehicle_of(a, ctx, {});
  const app::OngoingManeuver o = value_or_fail(app::evaluate_ongoing(ctx, q));
  if (format == "json")
    io.out << ongoing_maneuver_json(o).dump() << "\n";
  else
    print_ongoing(o, io.out);
  return 0;
}

// One candidate flown closed-loop, as `avk encounter run` flies it: own vehicle at the origin,
// the simulator setup of --vehicle/--sim-config (default the M200's, the bench's default) and its
// seed (--seed overrides; the bench flies every candidate with this one seed).
int fly(const std::vector<std::string>& rest, Io& io) {
  const Args a(rest,
               {"vehicle", "sim-config", "seed", "ticks", "own", "dheading", "speed", "contact",
                "horizon", "standoff", "path-step", "format"},
               {"jitter"}, {"contact"});
  const std::string format = a.get("format").value_or("json");
  if (format != "json" && format != "csv") throw UsageError("--format must be json or csv");
  const auto own = a.number_list("own", 2, "heading,speed");
  if (!own) throw UsageError("--own heading,speed is required");
  const auto dheading = a.number("dheading");
  if (!dheading) throw UsageError("--dheading (deg, + starboard) is required");
  const sim::SimSetup setup = sim_setup_from(a, io, "catamaran:m200");
  json body = {
      {"own", {{"x_m", 0.0}, {"y_m", 0.0}, {"heading_deg", (*own)[0]}, {"speed_mps", (*own)[1]}}},
      {"contacts", contacts_body(a)},
      {"dheading_deg", *dheading},
      {"seed", setup.scheduler.seed}};
  const std::pair<const char*, const char*> numbers[] = {{"speed", "speed_mps"},
                                                         {"horizon", "horizon_s"},
                                                         {"standoff", "standoff_m"},
                                                         {"path-step", "path_step_s"}};
  for (const auto& [option, field] : numbers)
    if (const auto v = a.number(option)) body[field] = *v;
  SimulateRequest request = value_or_fail(simulate_request(body));
  request.query.setup = setup;
  const app::SimulatedManeuver m = value_or_fail(app::simulate_maneuver(request.query));
  io.out << (format == "json" ? maneuver_flight_json(m, request).dump() + "\n"
                              : timed_path_csv(m.track, request.path_step_s));
  io.err << "maneuver fly: " << signed_deg(request.query.dheading_deg) << " deg on "
         << vehicle::to_string(setup.vehicle.kind) << " (seed " << request.query.seed << ")";
  for (std::size_t k = 0; k < m.cpa.size(); ++k)
    io.err << "; contact " << k << " CPA " << fixed(m.cpa[k].distance_m, 1) << " m at "
           << fixed(m.cpa[k].time_s, 1) << " s";
  io.err << "\n";
  return 0;
}

}  // namespace

int cmd_maneuver(const std::vector<std::string>& args, Io& io) {
  if (args.empty()) throw UsageError("expected 'maneuver evaluate|ongoing|fly'");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "evaluate") return evaluate(rest, io);
  if (args[0] == "ongoing") return ongoing(rest, io);
  if (args[0] == "fly") return fly(rest, io);
  throw UsageError("unknown subcommand 'maneuver " + args[0] + "'");
}

}  // namespace avk::server
