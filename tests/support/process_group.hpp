#pragma once
// A child in a process group of its own (gpsd, gpsfake and its gpsd), so that one signal reaches
// all of it: started with its output in a file, ended with SIGTERM to the group, SIGKILL to
// whatever is left after 10 s, and always a final SIGKILL to the group, so that no process of it
// outlives the test.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "support/c_strings.hpp"

extern char** environ;

namespace avk::testing {

// Starts args[0] (a path, or a name looked up on PATH) with stdin from /dev/null and stdout and
// stderr into output; the pid, or -1 when it could not be started.
inline pid_t spawn_process_group(const std::vector<std::string>& args, const std::string& output) {
  CStrings argv(args);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args.at(0).c_str(), &fa, &attr, argv.get(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

inline void stop_process_group(pid_t pid) {
  if (pid <= 0) return;
  ::kill(-pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // A member that outlived the leader (gpsfake's gpsd).
  ::kill(-pid, SIGKILL);
}

}  // namespace avk::testing
