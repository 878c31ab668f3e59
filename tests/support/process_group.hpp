#pragma once
// Ends a child started in a process group of its own (gpsd, gpsfake and its gpsd): SIGTERM to the
// group, SIGKILL to whatever is left after 10 s, and always a final SIGKILL to the group, so that
// no process of it outlives the test.

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <thread>

namespace avk::testing {

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
