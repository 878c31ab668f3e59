#pragma once
// Command-line options of the form `--name value` and `--flag`, with errors that name the option.

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace avk::server {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown when a command's words hold --help or -h: the answer is the command's usage (exit 0).
// Not a std::exception, so that no handler's catch of failures takes it for one.
struct HelpRequested {};

class Args {
 public:
  // value_options take a value; flag_options do not. --help or -h anywhere throws HelpRequested
  // (before any other word is looked at); anything else starting with "--" is an error; other
  // words are positional.
  // repeatable_options may be given more than once (`--mission 1 --mission 2`).
  Args(const std::vector<std::string>& words, const std::set<std::string>& value_options,
       const std::set<std::string>& flag_options = {},
       const std::set<std::string>& repeatable_options = {});

  std::optional<std::string> get(const std::string& name) const;
  std::string require(const std::string& name) const;
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  std::optional<double> number(const std::string& name) const;  // finite, else UsageError
  // "a,b,c": exactly `count` finite numbers; the UsageError names the option and `shape`.
  std::optional<std::vector<double>> number_list(const std::string& name, std::size_t count,
                                                 const std::string& shape) const;
  // The same for every value of a repeatable option, in order.
  std::vector<std::vector<double>> number_lists(const std::string& name, std::size_t count,
                                                const std::string& shape) const;
  std::vector<std::string> all(const std::string& name) const;  // every value given, in order
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::set<std::string> flags_;
  std::vector<std::string> positional_;
};

}  // namespace avk::server
