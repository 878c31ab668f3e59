#pragma once
// A real gpsd serving a log of NMEA/AIVDM sentences on a free loopback port, through gpsfake
// (gpsd-clients): gpsfake starts its own gpsd (listening on loopback only, as gpsd does without
// -G), waits for the first client and then feeds it the log, line by line every cycle_s seconds,
// over and over. The destructor ends gpsfake and its gpsd (the process group they share) in every
// path, waiting for gpsfake so that no process outlives the test.

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/c_strings.hpp"
#include "support/process_group.hpp"
#include "support/temp_dir.hpp"

extern char** environ;

namespace avk::testing {

// A loopback TCP port nobody listens on at the moment of asking (the kernel's pick for port 0).
inline int free_loopback_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("socket failed");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    ::close(fd);
    throw std::runtime_error("bind failed");
  }
  ::close(fd);
  return ntohs(a.sin_port);
}

class Gpsfake {
 public:
  // port 0: a free one.
  explicit Gpsfake(const std::filesystem::path& log, int port = 0, double cycle_s = 0.05)
      : dir_("gpsfake"), port_(port != 0 ? port : free_loopback_port()) {
    output_ = (dir_.path() / "gpsfake.out").string();
    std::vector<std::string> args = {
        "gpsfake", "-q",  "-c",        std::to_string(cycle_s), "-P", std::to_string(port_),
        "-W",      "600", log.string()};
    CStrings argv(args);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, output_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    // A process group of its own, gpsd included, so that one signal reaches both.
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    const int rc = posix_spawnp(&pid_, "gpsfake", &fa, &attr, argv.get(), environ);
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) throw std::runtime_error("cannot start gpsfake (scripts/setup installs it)");
  }
  ~Gpsfake() { stop(); }
  Gpsfake(const Gpsfake&) = delete;
  Gpsfake& operator=(const Gpsfake&) = delete;

  int port() const { return port_; }
  std::string port_text() const { return std::to_string(port_); }

  // What gpsfake and gpsd printed, for failure messages.
  std::string output() const {
    std::ifstream f(output_);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }

  // Ends gpsfake and gpsd (support/process_group.hpp).
  void stop() {
    stop_process_group(pid_);
    pid_ = -1;
  }

 private:
  TempDir dir_;
  int port_;
  std::string output_;
  pid_t pid_ = -1;
};

}  // namespace avk::testing
