#include "server/cli/usage.hpp"

#include <algorithm>
#include <ostream>

namespace avk::server {

const std::vector<CommandUsage>& command_usages() {
  static const std::vector<CommandUsage> usages = {
      {"turn",
       {"normalize"},
       "  avk turn normalize [FILE|-] [--format text|json]\n"
       "      read turn records (text records or JSON, one a line), print them normalised\n"},
      {"ckt",
       {"build"},
       "  avk ckt build --turns FILE [--out FILE] [--format json|csv] [--vehicle ID]\n"
       "                [--vehicle-length M] [--fit arc_length_spline|poly4_xy] [--epsilon M]\n"
       "      build the Cached Kinematics Table from turn records and write the CKT file\n"},
      {"ckt",
       {"export"},
       "  avk ckt export (--turns FILE | --ckt FILE) [--out FILE] [--format json|csv]\n"
       "      write a CKT file (JSON) or its vertices as CSV\n"},
      {"ckt",
       {"import"},
       "  avk ckt import FILE [--out FILE] [--format json|csv]\n"
       "      check a CKT file and summarise it; nothing partial is ever loaded\n"},
      {"ckt",
       {"query"},
       "  avk ckt query --ckt FILE --speed M/S --dheading DEG [--x M --y M --heading DEG]\n"
       "                [--format json|csv] [--current EAST,NORTH]\n"
       "                [--speed-reference over_ground|through_water]\n"
       "      predicted trajectory of one turn (placed at a pose when one is given)\n"},
      {"sim",
       {"turn"},
       "  avk sim turn --speed M/S --dheading DEG\n"
       "               [--vehicle usim|catamaran[:m200|:heron|:otter]]\n"
       "               [--seed N] [--ticks plant=4,controller=4,helm=4] [--csv FILE]\n"
       "               [--sim-config FILE] [--jitter] [--threshold DEG]\n"
       "               [--realtime [--realtime-factor K]]\n"
       "      one steady-then-turn run; the trajectory as CSV\n"},
      {"sim",
       {"variability"},
       "  avk sim variability --speed M/S --dheading DEG [--repeats 77] [--jitter]\n"
       "               [--sweep-ticks] [--vehicle ...] [--sim-config FILE] [--seed N]\n"
       "      advance/transfer per repetition and their coefficient of variation\n"},
      {"mission",
       {"validate"},
       "  avk mission validate --config FILE [--vehicle KIND]\n"
       "      check a mission file; every problem is listed with its field\n"},
      {"mission",
       {"run"},
       "  avk mission run --config FILE --db FILE --sim [--vehicle KIND] [--sim-config FILE]\n"
       "                  [--seed N] [--realtime [--realtime-factor K]] [--quiet]\n"
       "      run a collection mission on the simulator; every turn is stored\n"
       "      (with --db postgresql://...: [--station-id NAME] [--spool FILE], writes wait in\n"
       "      the spool while the server is away, docs/postgresql.md)\n"
       "  avk mission run --config FILE --db FILE --m200 HOST[:29500] [--datum LAT,LON]\n"
       "                  [--pid m200_in_water|thesis_sim] [--controller-hz 10]\n"
       "                  [--realtime-factor K] [--vehicle-id ID]\n"
       "      the same on a Kingfisher M200 over its frontseat link (K matches an emulator's)\n"},
      {"mission",
       {"resume"},
       "  avk mission resume ID --db FILE (--sim | --m200 HOST:PORT)\n"
       "      go on with an interrupted or paused mission: the turns not yet done\n"},
      {"mission",
       {"list"},
       "  avk mission list --db FILE\n"
       "      the stored missions with their status and turn counts\n"},
      {"mission",
       {"report"},
       "  avk mission report ID --db FILE\n"
       "      a mission's report: how it went, cell by cell\n"},
      {"mission",
       {"wait"},
       "  avk mission wait ID --db FILE [--poll 1]\n"
       "      follows a mission another process runs (avk serve): each turn as it is stored,\n"
       "      then how it ended (exit 0 when done)\n"},
      {"mission",
       {"export"},
       "  avk mission export ID --db FILE --out FILE [--format mcap] [--compression zstd|none]\n"
       "                  [--datum LAT,LON]\n"
       "      the mission as an MCAP recording for Foxglove/Lichtblick (docs/foxglove.md);\n"
       "      with a datum it carries positions on the earth too\n"},
      {"db",
       {"copy"},
       "  avk db copy --from FILE_OR_URL --to FILE_OR_URL\n"
       "      everything a database holds into an empty one, SQLite file or PostgreSQL\n"
       "      (postgresql://USER@HOST/DB or a libpq string), ids kept, doubles exact,\n"
       "      every table's rows counted in both (docs/postgresql.md)\n"},
      {"import",
       {"mcap"},
       "  avk import mcap FILE --db FILE\n"
       "      a mission exported by a station, as a new mission (everything or nothing)\n"},
      {"ckt",
       {"build", "export"},
       "  avk ckt build|export --db FILE [--mission ID]... [--vehicle ID] [--out FILE]\n"
       "                  [--include-harvested]  (collection turns only without it)\n"},
      {"turns",
       {"harvest"},
       "  avk turns harvest --db FILE (--mission ID | --all [--vehicle ID])\n"
       "                  [--format table|json]\n"
       "      turns harvested from a mission's navigation wherever the conditions of a\n"
       "      measured turn held before a step of the desired heading; the others counted\n"
       "      by reason (docs/harvest.md)\n"},
      {"ckt",
       {"yaw-rate"},
       "  avk ckt yaw-rate --db FILE [--vehicle ID] [--yaw-rate DPS]... [--model ID]\n"
       "                  [--no-model] [--out FILE]\n"
       "      the table over initial yaw rate (schema 4); coverage and the model's error\n"
       "      against measured cells on stderr\n"},
      {"model",
       {"fit"},
       "  avk model fit --db FILE --mission ID... [--form thesis|invariant] [--history S]\n"
       "                  [--refine] [--ridge auto|L] [--rate HZ] [--vehicle ID]\n"
       "      fit the black-box yaw model to missions' navigation and store it\n"},
      {"model",
       {"sweep"},
       "  avk model sweep --db FILE --mission ID... [--form thesis|invariant] [--refine]\n"
       "                  [--ridge auto|L] [--rate HZ] [--vehicle ID] [--format table|csv|json]\n"
       "      the model's validation error per history length (thesis Fig. 3-9)\n"},
      {"model",
       {"list"},
       "  avk model list --db FILE [--vehicle ID]\n"
       "      the stored models\n"},
      {"model",
       {"show"},
       "  avk model show --db FILE --model ID\n"
       "      one stored model\n"},
      {"predict",
       {},
       "  avk predict --db FILE --speed M/S --dheading DEG --method avk|model|instantaneous\n"
       "                  [--model ID] [--speed-model] [--x M --y M --heading DEG]\n"
       "                  [--corridor P]  (avk: the band holding P of the turns, default 0.9)\n"
       "                  [--current live|none|EAST,NORTH]  (default: over ground where the\n"
       "                   station knows the current; none: through the water)\n"
       "                  [--speed-reference over_ground|through_water]  (the speed loop's)\n"
       "                  [--initial-yaw-rate DPS]  (the yaw rate when the turn is commanded,\n"
       "                  + clockwise; avk: the table over initial yaw rate, model: started at\n"
       "                  it)\n"
       "                  [--speed-after M/S]  (the speed commanded with the new heading:\n"
       "                   measured cells of the pair, else the turn at --speed re-timed)\n"
       "                  [--without-mission ID]  (predicted by what never saw that mission:\n"
       "                   avk a table of the other missions' turns, model one not trained on\n"
       "                   it)\n"
       "      one turn's predicted trajectory\n"},
      {"maneuver",
       {"evaluate"},
       "  avk maneuver evaluate --db FILE --own X,Y,HEADING,SPEED --contact X,Y,COURSE,SPEED\n"
       "                  [--contact ...] [--vehicle ID] [--standoff 10] [--horizon 120]\n"
       "                  [--method avk|model|instantaneous] [--model ID] [--step 5]\n"
       "                  [--speed M/S] [--corridor 0.9] [--no-corridor] [--format table|json]\n"
       "                  [--current live|EAST,NORTH]\n"
       "      every candidate heading change scored by its CPA to the contacts, and the choice\n"},
      {"maneuver",
       {"ongoing"},
       "  avk maneuver ongoing --db FILE --start X,Y,HEADING --dheading DEG --speed M/S\n"
       "                  --elapsed S [--measured X,Y] [--method ...] [--format table|json]\n"
       "      where a maneuver in progress should be now, and how far the vehicle is from it\n"},
      {"maneuver",
       {"fly"},
       "  avk maneuver fly --own HEADING,SPEED --dheading DEG --contact X,Y,COURSE,SPEED\n"
       "                  [--contact ...] [--vehicle KIND (catamaran:m200)] [--sim-config FILE]\n"
       "                  [--seed N] [--horizon 120] [--speed M/S] [--standoff M]\n"
       "                  [--path-step 0.5] [--format json|csv]\n"
       "      one candidate flown in the simulator as the encounter bench flies it (own vehicle\n"
       "      at the origin): the flown track and the actual CPA per contact\n"},
      {"compare",
       {},
       "  avk compare --db FILE [--model ID] [--format table|csv|json]\n"
       "              [--scoring predictive|in_sample] [--metric path|thesis_mse]\n"
       "              [--corridor P] [--mission ID]...\n"
       "              [--test-mission ID]...  (judge the table on other turns)\n"
       "      the prediction methods compared on the stored turns\n"},
      {"encounter",
       {"run"},
       "  avk encounter run --scenarios FILE --db FILE [--vehicle-id ID]\n"
       "                  [--vehicle KIND (catamaran:m200)] [--sim-config FILE] [--seed N]\n"
       "                  [--method avk|model|instantaneous|all] [--step DEG] [--threads 2]\n"
       "                  [--format table|json|csv] [--current estimated|none]\n"
       "                  [--sea-seeds 1,2] [--max-risk 0.05] [--rule risk|corridor]\n"
       "                  [--colregs] [--speed-reference over_ground|through_water]\n"
       "                  [--ray-band]\n"
       "      the encounter bench: each method's maneuver choice flown in the simulator, and\n"
       "      every candidate flown (once per sea seed) to know whether a safe one existed and\n"
       "      how well the predicted risk is calibrated\n"},
      {"current",
       {"estimate"},
       "  avk current estimate --db FILE --mission ID [--store] [--leg S] [--from legs|turns]\n"
       "                  [--format text|json]\n"
       "      the current a mission flew in, from its steady legs (or from its turns against\n"
       "      the table of the other missions); --store keeps it and puts the mission's turns\n"
       "      in the water frame (the table is then built from them)\n"},
      {"current",
       {"show"},
       "  avk current show --db FILE [--vehicle ID] [--format text|json]\n"
       "      the station's latest estimate for the vehicle\n"},
      {"current",
       {"compare"},
       "  avk current compare --db FILE --mission ID... --test-mission ID...\n"
       "                  [--format text|json]\n"
       "      the table of some missions predicting the turns of others flown in another\n"
       "      current: path error with the current compensated and without\n"},
      {"vehicle",
       {"motion"},
       "  avk vehicle motion --db FILE [--vehicle ID] [--format text|json]\n"
       "      what the vehicle's steady legs say: which speed its loop holds (over ground or\n"
       "      through the water), how fast a straight-line prediction's error grows, and the\n"
       "      current it was last seen in\n"},
      {"encounter",
       {"generate"},
       "  avk encounter generate [--seed N] [--count 60]\n"
       "      a reproducible scenario file (head-on, crossing, overtaking, several contacts)\n"},
      {"band",
       {"coverage"},
       "  avk band coverage --db FILE --test-mission ID... [--mission ID]... [--vehicle ID]\n"
       "                  [--share 0.9] [--after 60]\n"
       "                  [--speed-reference over_ground|through_water] [--format text|json]\n"
       "      is the position band honest: the share of the test missions' positions, at equal\n"
       "      time, inside the band predicted by the table of the other missions\n"},
      {"serve",
       {},
       "  avk serve [--db FILE|URL] [--station-id NAME] [--spool FILE] [--token-file FILE]\n"
       "                  [--sim [--vehicle KIND] [--sim-config FILE]\n"
       "                  | --m200 HOST:PORT [--pid P] | --vehicles FLEET.json]\n"
       "                  [--datum LAT,LON] [--realtime-factor K]\n"
       "                  [--ais HOST:PORT (gpsd, with --datum)] [--standoff 20] [--watch-horizon "
       "60]\n"
       "                  [--bind 127.0.0.1] [--port 8080] [--web DIR] [--token T]\n"
       "                  [--allow-host NAME]... [--allow-origin ORIGIN]...\n"
       "                  [--max-connections 512] [--max-connections-per-address 64]\n"
       "                  [--max-streams-per-address 256] [--request-workers 4]\n"
       "                  [--request-queue 64] [--expensive-requests 2]\n"
       "                  [--expensive-requests-per-address 4]\n"
       "      the ground station: REST + WebSocket API under /api/v1 and the dashboard;\n"
       "      --vehicles runs a fleet (examples/fleet.json), each vehicle on its own loop;\n"
       "      --ais watches AIS traffic decoded by gpsd (docs/ais.md); the collision watch\n"
       "      warns when two vehicles (or a vehicle and a contact) are predicted closer than\n"
       "      --standoff m within --watch-horizon s; --db postgresql://USER@HOST/DB (or a\n"
       "      libpq string) shares a PostgreSQL database with other stations\n"
       "      (docs/postgresql.md)\n"},
      {"traffic",
       {},
       "  avk traffic --scenario FILE --udp HOST:PORT [--interval 2] [--realtime-factor K]\n"
       "                  [--duration S]\n"
       "      simulated AIS traffic: the scenario's contacts (examples/traffic-charles.json)\n"
       "      as AIVDM over UDP to gpsd (gpsd udp://HOST:PORT); runs until SIGINT/SIGTERM\n"},
      {"frontseat-emulator",
       {},
       "  avk frontseat-emulator [--port 29500] [--bind 127.0.0.1] [--vehicle catamaran:m200]\n"
       "                  [--sim-config FILE] [--datum LAT,LON] [--seed N]\n"
       "                  [--realtime-factor K] [--start X,Y,HEADING] [--drop F]\n"
       "                  [--corrupt F] [--nav-delay S] [--burst N] [--watchdog S]\n"
       "      a Kingfisher M200 frontseat (Clearpath protocol over TCP) on the simulated\n"
       "      catamaran, for trying a backseat without a boat; runs until SIGINT/SIGTERM\n"},
      {"import",
       {"alog"},
       "  avk import alog FILE --db FILE [--vehicle NAME] [--names NAV_X=X,NAV_Y=Y,...]\n"
       "                  [--turn-record VAR] [--threshold DEG] [--speed-tolerance M/S]\n"
       "                  [--max-yaw-rate DEG/S] [--harvest]\n"
       "      a MOOS-IvP .alog as a mission: navigation, and turns from its turn records or\n"
       "      from steps in DESIRED_HEADING; malformed lines are counted, not fatal;\n"
       "      --harvest stores those steps' turns as harvested (avk turns harvest)\n"},
  };
  return usages;
}

namespace {

bool matches(const CommandUsage& u, std::string_view command, std::string_view subcommand) {
  if (u.command != command) return false;
  return subcommand.empty() ||
         std::find(u.subcommands.begin(), u.subcommands.end(), subcommand) != u.subcommands.end();
}

}  // namespace

bool knows_command(std::string_view command, std::string_view subcommand) {
  const auto& all = command_usages();
  return std::any_of(all.begin(), all.end(),
                     [&](const CommandUsage& u) { return matches(u, command, subcommand); });
}

void print_usage(std::ostream& out, std::string_view command, std::string_view subcommand) {
  if (command.empty()) {
    out << "usage: avk <command> [options]   (avk <command> [<subcommand>] --help: its own)\n\n";
    for (const auto& u : command_usages())
      out << u.text;
    return;
  }
  out << "usage:\n";
  for (const auto& u : command_usages())
    if (matches(u, command, subcommand)) out << u.text;
}

}  // namespace avk::server
