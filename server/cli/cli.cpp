#include "server/cli/cli.hpp"

#include <ostream>

namespace avk::server {

namespace {
void usage(std::ostream& out) {
  out << "usage: avk <command> [options]\n"
         "commands:\n"
         "  turn normalize   read turn records, print them normalised\n"
         "  ckt build|export|import|query\n";
}
}  // namespace

int run_cli(const std::vector<std::string>& args, std::istream&, std::ostream& out,
            std::ostream& err) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    usage(args.empty() ? err : out);
    return args.empty() ? 2 : 0;
  }
  err << "avk: unknown command '" << args[0] << "'\n";
  usage(err);
  return 2;
}

}  // namespace avk::server
