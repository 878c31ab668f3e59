#pragma once
// A real gpsd reading AIVDM from a UDP source on loopback (`gpsd -N -n -S PORT udp://127.0.0.1:U`),
// as the simulator deployment runs it behind `avk traffic`. Its own process group; the destructor
// ends it in every path.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/c_strings.hpp"
#include "support/gpsfake.hpp"
#include "support/process_group.hpp"
#include "support/temp_dir.hpp"

extern char** environ;

namespace avk::testing {

class GpsdUdp {
 public:
  GpsdUdp() : dir_("gpsd_udp"), port_(free_loopback_port()), udp_port_(free_loopback_port()) {
    output_ = (dir_.path() / "gpsd.out").string();
    std::vector<std::string> args = {"gpsd", "-N", "-n", "-S", std::to_string(port_),
                                     "udp://127.0.0.1:" + std::to_string(udp_port_)};
    CStrings argv(args);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, output_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    // gpsd lives in /usr/sbin, which a user's PATH may leave out.
    int rc = posix_spawn(&pid_, "/usr/sbin/gpsd", &fa, &attr, argv.get(), environ);
    if (rc != 0) rc = posix_spawnp(&pid_, "gpsd", &fa, &attr, argv.get(), environ);
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) throw std::runtime_error("cannot start gpsd (scripts/setup installs it)");
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
