#pragma once
// What `avk --help`, `avk <command> --help` and `avk <command> <subcommand> --help` (or -h)
// print: one table of the commands the CLI knows, each usage with the subcommands it documents,
// so the whole usage and each command's own are the same text.

#include <iosfwd>
#include <string_view>
#include <vector>

namespace avk::server {

struct CommandUsage {
  std::string_view command;                   // "mission"
  std::vector<std::string_view> subcommands;  // {"run"}; empty for a command without any
  std::string_view text;                      // "  avk mission run ...\n      what it does\n"
};

// Every command and subcommand the CLI knows, in the order `avk --help` lists them.
const std::vector<CommandUsage>& command_usages();

// Whether the CLI knows the command (and, when given, that subcommand of it).
bool knows_command(std::string_view command, std::string_view subcommand = {});

// The usage of everything (no command), of one command (all its subcommands), or of one
// subcommand. Nothing is printed for a command the CLI does not know.
void print_usage(std::ostream& out, std::string_view command = {},
                 std::string_view subcommand = {});

}  // namespace avk::server
