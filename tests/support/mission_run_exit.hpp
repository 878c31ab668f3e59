#pragma once
// How an `avk mission run` child ended: whether it exited 0, its output, and the turns it
// finished ("N turns finished this run"), waited for up to ten minutes.

#include <sys/wait.h>

#include <chrono>
#include <cstdint>
#include <regex>
#include <string>

#include "support/polling.hpp"

namespace avk::testing {

struct MissionRunExit {
  bool exited_0 = false;  // exited by itself with status 0
  std::string output;
  std::int64_t turns_finished = -1;  // -1: not printed
};

inline MissionRunExit finished_mission_run(pid_t child, const std::string& log) {
  MissionRunExit r;
  int status = 0;
  const bool ended = within(std::chrono::seconds(600),
                            [&] { return ::waitpid(child, &status, WNOHANG) == child; });
  r.output = file_text(log);
  r.exited_0 = ended && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::smatch m;
  if (std::regex_search(r.output, m, std::regex(R"((\d+) turns finished this run)")))
    r.turns_finished = std::stoll(m[1]);
  return r;
}

}  // namespace avk::testing
