// avk serve: the ground station. The REST + WebSocket API and the dashboard over one database,
// with the vehicle missions run on: the simulator (--sim) or an M200 over its frontseat link
// (--m200 HOST:PORT).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <random>
#include <ranges>
#include <string_view>

#include "app/context.hpp"
#include "app/missions.hpp"
#include "app/station_identity.hpp"
#include "app/tiles/map_tiles.hpp"
#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/database_location.hpp"
#include "server/cli/db_selection.hpp"
#include "server/cli/files.hpp"
#include "server/cli/fleet_file.hpp"
#include "server/cli/m200_options.hpp"
#include "server/cli/sim_options.hpp"
#include "server/cli/station_options.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "server/token_strength.hpp"

namespace avk::server {

namespace {

namespace fs = std::filesystem;

std::string default_db_path() {
  const char* xdg = std::getenv("XDG_DATA_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = xdg && *xdg     ? fs::path(xdg)
                        : home && *home ? fs::path(home) / ".local" / "share"
                                        : fs::current_path();
  fs::create_directories(base / "avk-station");
  return (base / "avk-station" / "station.db").string();
}

std::string random_token() {
  std::random_device rd;
  static const char* hex = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 32; ++i)
    t += hex[rd() % 16];
  return t;
}

// A token an operator chose must be as hard to guess as the one we would generate
// (server/token_strength.hpp).
void check_user_token(const std::string& token) {
  if (const auto why = token_weakness(token)) throw UsageError("--token " + *why);
}

// The token lives beside the database, readable by its owner only, so a restart keeps the
// dashboard URL an operator already has. A token file others can read is refused rather than
// used: whoever could read it has had the token. created: whether this call wrote the file.
std::string station_token(const std::string& path, std::ostream& err, bool& created) {
  created = false;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if ((st.st_mode & 077) != 0) {
      char mode[8];
      std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
      throw std::runtime_error(
          "the token file " + path + " can be read by others (mode " + mode +
          "): remove it to have a new token written, or chmod 600 it if the token never left "
          "this account");
    }
    std::ifstream in(path);
    std::string t;
    std::getline(in, t);
    if (t.size() >= 16) return t;
    err << "serve: " << path << " holds no usable token; writing a new one\n";
    fs::remove(path);
  }
  const std::string t = random_token();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw std::runtime_error("cannot create the token file " + path);
  created = true;
  const std::string line = t + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  ::close(fd);
  if (!ok) throw std::runtime_error("cannot write the token file " + path);
  return t;
}

// Removes a file this start created unless the start got through (a failed start leaves
// nothing new behind).
class RemoveUnlessKept {
 public:
  void set(std::string path) { path_ = std::move(path); }
  void keep() { path_.clear(); }
  ~RemoveUnlessKept() {
    std::error_code ec;
    if (!path_.empty()) fs::remove(path_, ec);
  }

 private:
  std::string path_;
};

bool is_unspecified(const std::string& address) {
  return address == "0.0.0.0" || address == "::" || address == "[::]";
}

// --ais HOST:PORT: gpsd's socket. Its positions go on the local grid, so the datum is needed.
vehicle::GpsdAisOptions gpsd_options_from(const Args& a,
                                          const std::optional<vehicle::LatLon>& datum) {
  const std::string where = *a.get("ais");
  const auto colon = where.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == where.size() ||
      where.find_first_not_of("0123456789", colon + 1) != std::string::npos)
    throw UsageError("--ais " + where + ": expected HOST:PORT of gpsd (e.g. 127.0.0.1:2947)");
  if (!datum)
    throw UsageError("--ais needs --datum LAT,LON: AIS positions are placed on the local grid");
  vehicle::GpsdAisOptions o;
  o.host = where.substr(0, colon);
  o.port = where.substr(colon + 1);
  return o;
}

// ", vehicle sim-usim", ", vehicles alpha, bravo, charlie" or ", no vehicle".
std::string vehicles_text(const std::vector<app::VehicleLoopOptions>& vehicles) {
  if (vehicles.empty()) return ", no vehicle";
  std::string out = vehicles.size() == 1 ? ", vehicle " : ", vehicles ";
  for (std::size_t i = 0; i < vehicles.size(); ++i)
    out += (i ? ", " : "") + app::planned_vehicle_info(vehicles[i]).id;
  return out;
}

}  // namespace

int cmd_serve(const std::vector<std::string>& args, Io& io) {
  const Args a(args,
               {"db",
                "station-id",
                "spool",
                "token-file",
                "vehicle",
                "sim-config",
                "realtime-factor",
                "seed",
                "ticks",
                "m200",
                "bind",
                "port",
                "web",
                "token",
                "threads",
                "datum",
                "tiles",
                "pid",
                "controller-hz",
                "vehicle-id",
                "ais",
                "vehicles",
                "standoff",
                "watch-horizon",
                "allow-host",
                "allow-origin",
                "max-connections",
                "max-connections-per-address",
                "max-streams-per-address",
                "request-workers",
                "request-queue",
                "expensive-requests",
                "expensive-requests-per-address"},
               {"sim", "jitter"}, {"allow-host", "allow-origin"});
  if (a.flag("sim") && a.get("m200")) throw UsageError("give one vehicle: --sim or --m200");
  if (a.get("vehicles") && (a.flag("sim") || a.get("m200")))
    throw UsageError("--vehicles gives the whole fleet: leave out --sim and --m200");
  auto m200 = m200_options_from(a);  // option mistakes show before anything is opened
  const auto ais = a.get("ais") ? std::optional(gpsd_options_from(a, datum_from(a))) : std::nullopt;
  const double port = a.number("port").value_or(8080);
  if (port < 0 || port > 65535 || port != static_cast<int>(port))
    throw UsageError("--port must be a whole number from 0 to 65535");
  const double threads = a.number("threads").value_or(2);
  if (threads < 1 || threads > 64 || threads != static_cast<int>(threads))
    throw UsageError("--threads must be a whole number from 1 to 64");
  HttpServerOptions ho;
  const auto count_option = [&](const char* name, std::size_t& into) {
    const auto v = a.number(name);
    if (!v) return;
    if (*v < 1 || *v > 100000 || *v != static_cast<int>(*v))
      throw UsageError(std::string("--") + name + " must be a whole number from 1 to 100000");
    into = static_cast<std::size_t>(*v);
  };
  count_option("max-connections", ho.max_connections);
  count_option("max-connections-per-address", ho.max_connections_per_address);
  count_option("max-streams-per-address", ho.max_streams_per_address);
  count_option("request-queue", ho.request_queue);
  count_option("expensive-requests-per-address", ho.expensive_requests_per_address);
  count_option("request-workers", ho.request_workers);
  if (ho.request_workers > 256) throw UsageError("--request-workers must be at most 256");
  count_option("expensive-requests", ho.expensive_requests);
  if (ho.expensive_requests > ho.request_workers)
    throw UsageError("--expensive-requests (" + std::to_string(ho.expensive_requests) +
                     ") must not exceed --request-workers (" + std::to_string(ho.request_workers) +
                     ")");
  const auto allow_host = [&](const std::string& name, const std::string& source) {
    if (name.empty() || name.find_first_of(":/[] ") != std::string::npos)
      throw UsageError(source + " takes host names without port or scheme, not '" + name + "'");
    ho.allowed_hosts.push_back(name);
  };
  for (const auto& name : a.all("allow-host"))
    allow_host(name, "--allow-host");
  // The Docker image's command line is fixed, so its host names come from the environment:
  // AVK_ALLOW_HOSTS=a.example,b.example (spaces around a name and empty items are ignored).
  if (const char* env = std::getenv(kAllowHostsVariable)) {
    for (const auto part : std::string_view(env) | std::views::split(',')) {
      std::string_view name(part.begin(), part.end());
      const auto first = name.find_first_not_of(" \t");
      if (first == std::string_view::npos) continue;
      name = name.substr(first, name.find_last_not_of(" \t") - first + 1);
      allow_host(std::string(name), kAllowHostsVariable);
    }
  }
  for (auto origin : a.all("allow-origin")) {
    std::transform(origin.begin(), origin.end(), origin.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto sep = origin.find("://");
    const bool web = origin.starts_with("http://") || origin.starts_with("https://");
    if (!web || origin.size() == sep + 3 ||
        origin.find_first_of("/?# ", sep + 3) != std::string::npos)
      throw UsageError(
          "--allow-origin takes an origin such as https://app.foxglove.dev "
          "(scheme and host, optional port, no path), not '" +
          origin + "'");
    ho.allowed_origins.push_back(origin);
  }
  const double factor = realtime_factor_from(a);
  std::string user_token = a.get("token").value_or("");
  if (a.get("token")) check_user_token(user_token);
  // The map background is opened (and checked) before anything is written.
  std::shared_ptr<const app::tiles::MapTiles> tiles;
  if (const auto path = a.get("tiles")) {
    auto opened = app::tiles::open_map_tiles(*path);
    if (!opened) {
      std::string why = "--tiles: ";
      why += opened.error().message;
      throw UsageError(why);
    }
    tiles = *opened;
  }

  // The default location is made only when it is used: a user without a home can still give
  // --db.
  const std::string db_path = a.get("db") ? *a.get("db") : default_db_path();
  // A database server (PostgreSQL) has no file beside which the token could live: it goes to
  // --token-file, or beside the default database file.
  const bool server_db = app::is_database_server(db_path);
  apply_station_options(a);
  const std::string token_path =
      a.get("token-file").value_or((server_db ? default_db_path() : db_path) + ".token");
  StationOptions so;
  so.db_path = db_path;
  so.server_version = "avk-station 0.1.0";
  // Before anything is written there: a folder this user cannot write (a Docker bind mount
  // owned by root) is named with its owner and this process's uid, not as a failed token file.
  if (!server_db) check_database_location(db_path);
  RemoveUnlessKept new_token_file;
  if (user_token.empty()) {
    bool created = false;
    so.token = station_token(token_path, io.err, created);
    if (created) new_token_file.set(token_path);
  } else {
    so.token = user_token;
  }

  // The station clock continues after everything stored, so mission times never repeat.
  const double clock_start_s = [&db_path] {
    app::Context stored(db_path);
    return app::station_clock_start_s(stored);
  }();
  so.datum = datum_from(a);
  if (const auto s = a.number("standoff")) {
    if (!(*s > 0.0 && *s <= 1000.0)) throw UsageError("--standoff must be in (0, 1000] m");
    so.collision_watch->standoff_m = *s;
  }
  if (const auto h = a.number("watch-horizon")) {
    if (!(*h >= 5.0 && *h <= 600.0)) throw UsageError("--watch-horizon must be in [5, 600] s");
    so.collision_watch->horizon_s = *h;
  }
  so.tiles = tiles;
  so.ais = ais;
  if (const auto fleet = a.get("vehicles")) {
    so.vehicles =
        parse_fleet_file(*fleet, read_file(*fleet, io.in), factor, clock_start_s, so.datum);
  } else if (a.flag("sim")) {
    app::VehicleLoopOptions v;
    v.setup = sim_setup_from(a, io);
    v.setup.vehicle.id =
        vehicle_id_option(a, std::string("sim-") + vehicle::to_string(v.setup.vehicle.kind));
    v.realtime_factor = factor;
    v.start_clock_s = clock_start_s;
    so.vehicles.push_back(v);
  } else if (m200) {
    app::VehicleLoopOptions v;
    v.kind = vehicle::VehicleKind::m200;
    v.m200 = std::move(m200);
    v.realtime_factor = factor;
    v.start_clock_s = clock_start_s;
    so.vehicles.push_back(v);
  }
  ho.bind_address = a.get("bind").value_or("127.0.0.1");
  if (ho.bind_address == "[::]") ho.bind_address = "::";
  ho.port = static_cast<unsigned short>(port);
  ho.threads = static_cast<int>(threads);
  ho.server_version = so.server_version;
  const std::string web = a.get("web").value_or("web");
  if (fs::is_directory(web)) {
    ho.web_root = fs::canonical(web).string();
  } else if (a.get("web")) {
    throw UsageError("--web " + web + " is not a directory");
  }

  // Signals are taken by this thread alone (sigwait), so block them before any thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  StreamHub hub;
  Station station(so, hub);
  station.start();
  HttpServer http(ho, station, hub);
  http.start();
  new_token_file.keep();
  const bool everywhere = is_unspecified(ho.bind_address);
  const bool v6 = ho.bind_address.find(':') != std::string::npos;
  const std::string host = everywhere ? (v6 ? "[::1]" : "127.0.0.1")
                           : v6       ? "[" + ho.bind_address + "]"
                                      : ho.bind_address;
  io.out << "AVK Station on http://" << host << ":" << http.port() << "/ (database " << db_path
         << vehicles_text(so.vehicles) << ")\n"
         << "dashboard with control: http://" << host << ":" << http.port()
         << "/?token=" << so.token << std::endl;
  if (!ho.allowed_hosts.empty()) {
    io.out << "host names answered besides IP addresses and localhost:";
    for (const auto& name : ho.allowed_hosts)
      io.out << " " << name;
    io.out << std::endl;
  }
  if (tiles) {
    const auto& t = tiles->info();
    io.out << "map tiles: " << t.source << " " << *a.get("tiles") << " (" << t.format << ", zoom "
           << t.min_zoom << "-" << t.max_zoom << ")"
           << (so.datum ? "" : "; the dashboard draws them only with --datum") << std::endl;
  }
  const bool loopback_only =
      !everywhere && (ho.bind_address.starts_with("127.") || ho.bind_address == "::1");
  if (!loopback_only)
    io.err << "serve: WARNING: listening on " << ho.bind_address
           << ", so the API and the dashboard are reachable from other machines; they need the "
              "token for every request, reads included. From elsewhere use http://"
           << (everywhere ? std::string("<this machine's address>") : host) << ":" << http.port()
           << "/?token=<the token above>\n";
  int signal_number = 0;
  sigwait(&signals, &signal_number);
  io.err << "serve: " << (signal_number == SIGINT ? "SIGINT" : "SIGTERM")
         << ": pausing the mission, flushing, closing connections\n";
  station.shutdown();
  http.stop();
  pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  return 0;
}

}  // namespace avk::server
