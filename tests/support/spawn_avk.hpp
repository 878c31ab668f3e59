#pragma once
// Starts the real `avk` binary as a child process with stdout and stderr in a log file, for the
// tests that kill it (kill -9, SIGTERM) the way an operator or a power cut would.

#include <fcntl.h>
#include <spawn.h>
#include <sys/types.h>

#include <string>
#include <vector>

extern char** environ;

namespace avk::testing {

// Returns the child's pid, or -1 when it could not be started.
inline pid_t spawn_avk(const std::vector<std::string>& args, const std::string& log) {
  std::vector<std::string> argv_s = {AVK_BINARY};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, AVK_BINARY, &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

}  // namespace avk::testing
