#pragma once
// The text of a file of examples/ (a mission, a sim config), for tests that read the committed
// examples rather than copies of them.

#include <fstream>
#include <sstream>
#include <string>

namespace avk::testing {

inline std::string example_text(const std::string& name) {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/examples/" + name);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace avk::testing
