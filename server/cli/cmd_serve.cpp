// avk serve: the ground station. The REST + WebSocket API and the dashboard over one database,
// with the vehicle missions run on: the simulator (--sim) or an M200 over its frontseat link
// (--m200 HOST:PORT).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <random>

#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/m200_options.hpp"
#include "server/cli/sim_options.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "store/store.hpp"

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

// The token lives beside the database, readable by its owner only, so a restart keeps the
// dashboard URL an operator already has.
std::string station_token(const std::string& db_path, std::ostream& err) {
  const std::string path = db_path + ".token";
  if (std::ifstream in(path); in) {
    std::string t;
    std::getline(in, t);
    if (t.size() >= 16) return t;
    err << "serve: " << path << " holds no usable token; writing a new one\n";
    fs::remove(path);
  }
  const std::string t = random_token();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw std::runtime_error("cannot create the token file " + path);
  const std::string line = t + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  ::close(fd);
  if (!ok) throw std::runtime_error("cannot write the token file " + path);
  return t;
}

std::string vehicle_id(const VehicleLoopOptions& v) {
  return v.m200 ? v.m200->config.id : v.setup.vehicle.id;
}

}  // namespace

int cmd_serve(const std::vector<std::string>& args, Io& io) {
  const Args a(args,
               {"db", "vehicle", "sim-config", "realtime-factor", "seed", "ticks", "m200", "bind",
                "port", "web", "token", "threads", "datum", "pid", "controller-hz", "vehicle-id"},
               {"sim", "jitter"});
  if (a.flag("sim") && a.get("m200")) throw UsageError("give one vehicle: --sim or --m200");
  auto m200 = m200_options_from(a);  // option mistakes show before anything is opened
  const std::string db_path = a.get("db").value_or(default_db_path());
  StationOptions so;
  so.db_path = db_path;
  so.server_version = "avk-station 0.1.0";
  so.token = a.get("token").value_or("");
  if (!so.token.empty() && so.token.size() < 16)
    throw UsageError("--token must be at least 16 characters");
  if (so.token.empty()) so.token = station_token(db_path, io.err);
  const double port = a.number("port").value_or(8080);
  if (port < 0 || port > 65535 || port != static_cast<int>(port))
    throw UsageError("--port must be a whole number from 0 to 65535");
  const double threads = a.number("threads").value_or(2);
  if (threads < 1 || threads > 64 || threads != static_cast<int>(threads))
    throw UsageError("--threads must be a whole number from 1 to 64");
  const double factor = realtime_factor_from(a);

  const double clock = store::Store(db_path).station_clock_end_s();
  if (a.flag("sim")) {
    VehicleLoopOptions v;
    v.setup = sim_setup_from(a, io);
    v.setup.vehicle.id = "sim-" + v.setup.vehicle.kind;
    v.realtime_factor = factor;
    // The station clock continues after everything stored, so mission times never repeat.
    v.start_clock_s = clock + 1.0;
    so.vehicle = v;
  } else if (m200) {
    VehicleLoopOptions v;
    v.m200 = std::move(m200);
    v.realtime_factor = factor;
    v.start_clock_s = clock + 1.0;
    so.vehicle = v;
  }
  HttpServerOptions ho;
  ho.bind_address = a.get("bind").value_or("127.0.0.1");
  ho.port = static_cast<unsigned short>(port);
  ho.threads = static_cast<int>(threads);
  ho.server_version = so.server_version;
  const std::string web = a.get("web").value_or("web");
  if (fs::is_directory(web)) {
    ho.web_root = fs::canonical(web).string();
  } else if (a.get("web")) {
    throw UsageError("--web " + web + " is not a directory");
  }
  if (so.vehicle)
    ho.body_limit_by_path["/api/v1/vehicles/" + vehicle_id(*so.vehicle) + "/ckt/import"] = 64u
                                                                                           << 20;

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
  const std::string host = ho.bind_address == "0.0.0.0" ? "127.0.0.1" : ho.bind_address;
  io.out << "AVK Station on http://" << host << ":" << http.port() << "/ (database " << db_path
         << (so.vehicle ? ", vehicle " + vehicle_id(*so.vehicle) : std::string(", no vehicle"))
         << ")\n"
         << "dashboard with control: http://" << host << ":" << http.port()
         << "/?token=" << so.token << std::endl;
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
