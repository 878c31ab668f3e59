#pragma once
// The one mapping of the use cases' errors to the command line: a message on stderr naming the
// command, and the exit code (1: the data cannot answer, 3: a fault of the station itself).

#include <string>

#include "app/result.hpp"
#include "server/cli/commands.hpp"

namespace avk::server {

int report_error(const app::Error& e, Io& io, const std::string& command);

// The value of a use case, or the error thrown as CliFailure for run_cli to report.
class CliFailure : public std::exception {
 public:
  explicit CliFailure(app::Error e) : error_(std::move(e)) {}
  const app::Error& error() const { return error_; }
  const char* what() const noexcept override { return error_.message.c_str(); }

 private:
  app::Error error_;
};

template <class T>
T value_or_fail(app::Result<T> r) {
  if (!r) throw CliFailure(r.error());
  return std::move(r).value();
}

}  // namespace avk::server
