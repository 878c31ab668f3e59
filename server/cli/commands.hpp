#pragma once
// The avk subcommands. Each takes the words after its name and returns the process exit code:
// 0 success, 1 a failure of the input (bad file, out of range, nothing stored to answer with),
// 2 a usage error, 3 a fault of the station (a corrupt database).

#include <iosfwd>
#include <string>
#include <vector>

namespace avk::app {
struct HarvestReport;
}
namespace avk::kinematics {
struct CurrentEstimate;
struct SpeedReferenceEvidence;
struct DriftScatter;
}  // namespace avk::kinematics

namespace avk::server {

struct Io {
  std::istream& in;
  std::ostream& out;
  std::ostream& err;
};

int cmd_turn(const std::vector<std::string>& args, Io& io);
int cmd_harvest(const std::vector<std::string>& args, Io& io);  // avk turns harvest
// A harvest's counts as the CLI prints them (avk turns harvest, avk import alog --harvest).
void print_harvest(const app::HarvestReport& r, std::ostream& out);
int cmd_ckt(const std::vector<std::string>& args, Io& io);
int cmd_sim(const std::vector<std::string>& args, Io& io);
int cmd_mission(const std::vector<std::string>& args, Io& io);
int cmd_model(const std::vector<std::string>& args, Io& io);
int cmd_compare(const std::vector<std::string>& args, Io& io);
int cmd_predict(const std::vector<std::string>& args, Io& io);
int cmd_maneuver(const std::vector<std::string>& args, Io& io);
int cmd_import(const std::vector<std::string>& args, Io& io);
int cmd_db(const std::vector<std::string>& args, Io& io);
// avk mission export (MCAP) and avk import mcap (cli/cmd_mcap.cpp).
int mission_export(const std::vector<std::string>& args, Io& io);
int import_mcap(const std::vector<std::string>& args, Io& io);
int cmd_serve(const std::vector<std::string>& args, Io& io);
int cmd_encounter(const std::vector<std::string>& args, Io& io);
int cmd_band(const std::vector<std::string>& args, Io& io);  // avk band coverage
int cmd_current(const std::vector<std::string>& args, Io& io);
int cmd_vehicle(const std::vector<std::string>& args, Io& io);  // avk vehicle motion
// "0.20 ± 0.01 m/s toward 182.0 ± 3.0° (east …, north … m/s; N pieces of evidence, residual …)"
void print_current_estimate(const kinematics::CurrentEstimate& e, std::ostream& out);
// "over_ground (rms over ground …, through the water …, separation … m/s over N legs)" or
// "undetermined (…)"; the line's end is the caller's.
void print_speed_reference(const kinematics::SpeedReferenceEvidence& e, std::ostream& out);
// "along … m/s, across … m/s (N legs of … s on average)"
void print_drift_scatter(const kinematics::DriftScatter& d, std::ostream& out);
int cmd_frontseat_emulator(const std::vector<std::string>& args, Io& io);
// avk traffic: a scenario's contacts as AIVDM over UDP to gpsd (cmd_traffic.cpp).
int cmd_traffic(const std::vector<std::string>& args, Io& io);

}  // namespace avk::server
