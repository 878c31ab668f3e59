#pragma once
// Waiting for something another process or thread does: a condition polled until it holds or a
// generous limit passes (a loaded machine may be slow; nothing is timed), and a child's log read
// whole for a failure message.

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace avk::testing {

// Polls `done` every 50 ms until it holds or `limit` passes; whether it held.
template <typename Done>
bool within(std::chrono::seconds limit, Done done) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return done();
}

inline std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace avk::testing
