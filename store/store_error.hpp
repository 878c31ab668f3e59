#pragma once
// The one error every store engine throws, so a caller handles a failure of the database without
// knowing which engine stands behind the repositories.

#include <stdexcept>
#include <string>

namespace avk::store {

// Any failure of the database: the engine's message and its own code (SQLite's extended result
// code; 0 when the failure is not the engine's, such as a corrupt stored document).
class StoreError : public std::runtime_error {
 public:
  explicit StoreError(const std::string& message, int engine_code = 0)
      : std::runtime_error(message), code_(engine_code) {}
  int engine_code() const { return code_; }

 private:
  int code_;
};

// The database server cannot be reached (refused, restarted, connection lost mid-statement):
// the write may be tried again later, unlike an error in what was written. Whether a statement
// that was running when the connection broke committed is unknown.
class StoreUnavailable : public StoreError {
 public:
  using StoreError::StoreError;
};

}  // namespace avk::store
