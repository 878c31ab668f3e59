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
    pid_ = spawn_process_group(args, output_);
    if (pid_ <= 0) throw std::runtime_error("cannot start gpsfake (scripts/setup installs it)");
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
