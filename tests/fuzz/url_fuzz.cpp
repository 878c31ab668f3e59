// libFuzzer target for the HTTP target, query and Origin decoding (server/http/url.cpp, which has
// no Beast dependency), built by tests/CMakeLists.txt. Nothing may throw; decoding never makes
// text longer; a split target puts back together to what came in.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>

#include "server/http/url.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace avk::server;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  for (bool plus : {false, true})
    if (percent_decode(input, plus).size() > input.size()) std::abort();
  const SplitTarget t = split_target(input);
  if (t.path.size() + t.query.size() > input.size()) std::abort();
  std::map<std::string, std::string> query;
  std::multimap<std::string, std::string> multi;
  parse_query(t.query, query, multi);
  if (query.size() > multi.size()) std::abort();
  for (const auto& [k, v] : query)
    if (multi.find(k) == multi.end()) std::abort();
  // Origin and Host from the two halves of the input.
  const std::size_t half = input.size() / 2;
  (void)same_origin(input.substr(0, half), input.substr(half));
  return 0;
}
