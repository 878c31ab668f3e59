#include <ostream>

#include "server/cli/args.hpp"
#include "server/cli/commands.hpp"
#include "server/cli/files.hpp"
#include "server/cli/turn_file.hpp"

namespace avk::server {

int cmd_turn(const std::vector<std::string>& args, Io& io) {
  if (args.empty() || args[0] != "normalize") {
    throw UsageError("expected 'turn normalize [FILE|-] [--format text|json]'");
  }
  const Args a({args.begin() + 1, args.end()}, {"format"});
  if (a.positional().size() > 1) throw UsageError("give at most one input file");
  const std::string path = a.positional().empty() ? "-" : a.positional()[0];
  std::optional<TurnFormat> format;
  if (const auto f = a.get("format")) {
    if (*f == "text") {
      format = TurnFormat::text;
    } else if (*f == "json") {
      format = TurnFormat::json;
    } else {
      throw UsageError("--format must be text or json, got '" + *f + "'");
    }
  }
  const auto records = parse_turn_file(read_file(path, io.in), path == "-" ? "stdin" : path);
  for (const auto& r : records) {
    io.out << format_turn(r.turn.normalized(), format.value_or(r.format)) << "\n";
  }
  return 0;
}

}  // namespace avk::server
