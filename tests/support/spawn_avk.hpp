#pragma once
// Starts the real `avk` binary as a child process with stdout and stderr in a log file, for the
// tests that kill it (kill -9, SIGTERM) the way an operator or a power cut would.

#include <fcntl.h>
#include <grp.h>
#include <spawn.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/c_strings.hpp"

extern char** environ;

namespace avk::testing {

inline std::vector<std::string> avk_argv(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {AVK_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

// Returns the child's pid, or -1 when it could not be started. `env` ("NAME=value") is added to
// this process's environment for the child only.
inline pid_t spawn_avk(const std::vector<std::string>& args, const std::string& log,
                       const std::vector<std::string>& env = {}) {
  CStrings argv(avk_argv(args));
  std::vector<std::string> env_all;
  for (char** e = environ; *e; ++e)
    env_all.emplace_back(*e);
  env_all.insert(env_all.end(), env.begin(), env.end());
  CStrings envp(std::move(env_all));
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, AVK_BINARY, &fa, nullptr, argv.get(), envp.get());
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

// What a child started as another user writes to its log when it could not become that user.
inline constexpr const char* kCannotChangeUser = "spawn_avk_as: cannot change user";

// Like spawn_avk, as user `uid` (group `gid`, no supplementary groups): a test running as root
// sees what an unprivileged process (the Docker image's user) sees. Needs the right to change
// user; without it the child writes kCannotChangeUser to the log and exits 126.
inline pid_t spawn_avk_as(uid_t uid, gid_t gid, const std::vector<std::string>& args,
                          const std::string& log) {
  CStrings argv(avk_argv(args));
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    if (::setgroups(0, nullptr) != 0 || ::setgid(gid) != 0 || ::setuid(uid) != 0) {
      if (::write(2, kCannotChangeUser, std::strlen(kCannotChangeUser)) < 0) ::_exit(125);
      ::_exit(126);
    }
    ::execve(AVK_BINARY, argv.get(), environ);
    ::_exit(127);
  }
  ::close(fd);
  return pid;
}

// A running `avk serve` and the loopback port it printed.
struct ServeProcess {
  pid_t pid = -1;
  unsigned short port = 0;
};

// Starts `avk serve` with these arguments and waits (20 s at most) for the address it prints
// once it listens; port stays 0 when it printed none.
inline ServeProcess spawn_serve(const std::vector<std::string>& args, const std::string& log,
                                const std::vector<std::string>& env = {}) {
  std::vector<std::string> all = {"serve"};
  all.insert(all.end(), args.begin(), args.end());
  ServeProcess p;
  p.pid = spawn_avk(all, log, env);
  const std::regex listening(R"(http://127\.0\.0\.1:(\d+)/)");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (p.pid > 0 && std::chrono::steady_clock::now() < deadline) {
    std::ifstream f(log);
    std::string line;
    std::smatch m;
    while (std::getline(f, line))
      if (std::regex_search(line, m, listening))
        p.port = static_cast<unsigned short>(std::stoi(m[1]));
    if (p.port) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return p;
}

}  // namespace avk::testing
