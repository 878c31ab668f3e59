#pragma once
// A real gpsd reading AIVDM from a UDP source on loopback (`gpsd -N -n -S PORT udp://127.0.0.1:U`),
// as the simulator deployment runs it behind `avk traffic`. Its own process group; the destructor
// ends it in every path.

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/gpsfake.hpp"
#include "support/process_group.hpp"
#include "support/temp_dir.hpp"

namespace avk::testing {

class GpsdUdp {
 public:
  GpsdUdp() : dir_("gpsd_udp"), port_(free_loopback_port()), udp_port_(free_loopback_port()) {
    output_ = (dir_.path() / "gpsd.out").string();
    // gpsd lives in /usr/sbin, which a user's PATH may leave out: there first, then on PATH.
    std::vector<std::string> args = {"/usr/sbin/gpsd",
                                     "-N",
                                     "-n",
                                     "-S",
                                     std::to_string(port_),
                                     "udp://127.0.0.1:" + std::to_string(udp_port_)};
    pid_ = spawn_process_group(args, output_);
    if (pid_ <= 0) {
      args[0] = "gpsd";
      pid_ = spawn_process_group(args, output_);
    }
    if (pid_ <= 0) throw std::runtime_error("cannot start gpsd (scripts/setup installs it)");
  }
  ~GpsdUdp() { stop_process_group(pid_); }
  GpsdUdp(const GpsdUdp&) = delete;
  GpsdUdp& operator=(const GpsdUdp&) = delete;

  std::string port_text() const { return std::to_string(port_); }
  // Where AIVDM is sent: HOST:PORT.
  std::string udp_source() const { return "127.0.0.1:" + std::to_string(udp_port_); }
  std::string output() const {
    std::ifstream f(output_);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }

 private:
  TempDir dir_;
  int port_;
  int udp_port_;
  std::string output_;
  pid_t pid_ = -1;
};

}  // namespace avk::testing
