#pragma once
// The avk subcommands. Each takes the words after its name and returns the process exit code:
// 0 success, 1 a failure of the input (bad file, out of range), 2 a usage error.

#include <iosfwd>
#include <string>
#include <vector>

namespace avk::server {

struct Io {
  std::istream& in;
  std::ostream& out;
  std::ostream& err;
};

int cmd_turn(const std::vector<std::string>& args, Io& io);
int cmd_ckt(const std::vector<std::string>& args, Io& io);
int cmd_sim(const std::vector<std::string>& args, Io& io);
int cmd_mission(const std::vector<std::string>& args, Io& io);
int cmd_model(const std::vector<std::string>& args, Io& io);
int cmd_compare(const std::vector<std::string>& args, Io& io);
int cmd_predict(const std::vector<std::string>& args, Io& io);
int cmd_import(const std::vector<std::string>& args, Io& io);
int cmd_serve(const std::vector<std::string>& args, Io& io);
int cmd_frontseat_emulator(const std::vector<std::string>& args, Io& io);

// Current UTC time as ISO 8601 (seconds).
std::string utc_now_iso8601();

}  // namespace avk::server
