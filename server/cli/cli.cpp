#include "server/cli/cli.hpp"

#include <exception>
#include <ostream>
#include <string_view>

#include "server/cli/app_error.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/usage.hpp"

namespace avk::server {

int run_cli(const std::vector<std::string>& args, std::istream& in, std::ostream& out,
            std::ostream& err) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_usage(args.empty() ? err : out);
    return args.empty() ? 2 : 0;
  }
  // A command's own usage, before its subcommand is asked for (`avk mission --help`).
  if (args.size() >= 2 && (args[1] == "--help" || args[1] == "-h") && knows_command(args[0])) {
    print_usage(out, args[0]);
    return 0;
  }
  Io io{in, out, err};
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (args[0] == "turn") return cmd_turn(rest, io);
    if (args[0] == "turns") {
      if (rest.empty() || rest[0] != "harvest") throw UsageError("expected 'turns harvest'");
      return cmd_harvest(std::vector<std::string>(rest.begin() + 1, rest.end()), io);
    }
    if (args[0] == "ckt") return cmd_ckt(rest, io);
    if (args[0] == "sim") return cmd_sim(rest, io);
    if (args[0] == "mission") return cmd_mission(rest, io);
    if (args[0] == "model") return cmd_model(rest, io);
    if (args[0] == "compare") return cmd_compare(rest, io);
    if (args[0] == "predict") return cmd_predict(rest, io);
    if (args[0] == "maneuver") return cmd_maneuver(rest, io);
    if (args[0] == "import") return cmd_import(rest, io);
    if (args[0] == "db") return cmd_db(rest, io);
    if (args[0] == "encounter") return cmd_encounter(rest, io);
    if (args[0] == "band") return cmd_band(rest, io);
    if (args[0] == "current") return cmd_current(rest, io);
    if (args[0] == "vehicle") return cmd_vehicle(rest, io);
    if (args[0] == "serve") return cmd_serve(rest, io);
    if (args[0] == "frontseat-emulator") return cmd_frontseat_emulator(rest, io);
    if (args[0] == "traffic") return cmd_traffic(rest, io);
  } catch (const HelpRequested&) {
    // --help or -h among a command's options (Args): its usage, or its subcommand's.
    const bool sub = args.size() > 1 && knows_command(args[0], args[1]);
    print_usage(out, args[0], sub ? std::string_view(args[1]) : std::string_view());
    return 0;
  } catch (const UsageError& e) {
    err << "avk " << args[0] << ": " << e.what() << "\n";
    return 2;
  } catch (const CliFailure& e) {
    return report_error(e.error(), io, args[0]);
  } catch (const std::exception& e) {
    err << "avk " << args[0] << ": " << e.what() << "\n";
    return 1;
  }
  err << "avk: unknown command '" << args[0] << "'\n";
  print_usage(err);
  return 2;
}

}  // namespace avk::server
