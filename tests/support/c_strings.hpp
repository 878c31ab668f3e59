#pragma once
// The argv or envp of a child process the tests start (spawn_avk.hpp, gpsfake.hpp).

#include <string>
#include <utility>
#include <vector>

namespace avk::testing {

// A null-terminated array of C strings over strings it owns: an argv or an envp.
class CStrings {
 public:
  explicit CStrings(std::vector<std::string> strings) : strings_(std::move(strings)) {
    for (auto& s : strings_)
      pointers_.push_back(s.data());
    pointers_.push_back(nullptr);
  }
  CStrings(const CStrings&) = delete;
  CStrings& operator=(const CStrings&) = delete;
  char** get() { return pointers_.data(); }

 private:
  std::vector<std::string> strings_;
  std::vector<char*> pointers_;
};

}  // namespace avk::testing
