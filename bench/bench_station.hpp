#pragma once
// The station the load benchmarks measure: a database holding one Figure 4-1 mission (so the CKT
// has turns; more with repeats), the station with its simulated usim vehicle, and the HTTP server
// on an ephemeral loopback port with two io threads (unless told otherwise) and the repository's
// web/ — as `avk serve --sim` runs it.

#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "server/cli/cli.hpp"
#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/temp_db.hpp"

namespace avk::bench {

struct BenchStation {
  // repeats: the Figure 4-1 mission's, flown before the server starts (more turns to read);
  // io_threads: the HTTP server's (`avk serve` runs 2).
  BenchStation(const std::string& name, const std::string& token, double realtime_factor,
               int repeats = 1, int io_threads = 2)
      : db(name) {
    std::ifstream example(std::string(AVK_SOURCE_DIR) + "/examples/thesis-fig4-1.json");
    std::stringstream text;
    text << example.rdbuf();
    const std::string config_path = db.path() + ".mission.json";
    std::ofstream(config_path) << std::regex_replace(text.str(), std::regex(R"("repeats": *\d+)"),
                                                     "\"repeats\": " + std::to_string(repeats));
    std::istringstream in;
    std::ostringstream out, err;
    const int rc = server::run_cli(
        {"mission", "run", "--config", config_path, "--db", db.path(), "--sim", "--quiet"}, in, out,
        err);
    std::filesystem::remove(config_path);
    if (rc != 0) throw std::runtime_error("the mission run failed: " + err.str());
    server::StationOptions so;
    so.db_path = db.path();
    so.token = token;
    so.server_version = "bench";
    app::VehicleLoopOptions v;
    v.setup = sim::default_sim_setup("usim");
    v.setup.vehicle.id = vehicle_id;
    v.realtime_factor = realtime_factor;
    v.start_clock_s = store::Store(db.path()).missions().station_clock_end_s() + 1.0;
    v.start = {0.0, -70.0, 0.0};
    so.vehicles.push_back(v);
    station = std::make_unique<server::Station>(so, hub);
    station->start();
    server::HttpServerOptions ho;
    ho.port = 0;
    ho.threads = io_threads;
    ho.server_version = "bench";
    // The dashboard as `avk serve` serves it from a checkout.
    ho.web_root = std::string(AVK_SOURCE_DIR) + "/web";
    http = std::make_unique<server::HttpServer>(ho, *station, hub);
    http->start();
  }
  ~BenchStation() {
    http->stop();
    station->shutdown();
  }
  unsigned short port() const { return http->port(); }

  static constexpr const char* vehicle_id = "sim-usim";
  testing::TempDb db;
  server::StreamHub hub;
  std::unique_ptr<server::Station> station;
  std::unique_ptr<server::HttpServer> http;
};

}  // namespace avk::bench
