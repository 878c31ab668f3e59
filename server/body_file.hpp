#pragma once
// A response body kept in a file instead of memory (a mission's MCAP export): the handler writes
// it to an unlinked temporary file, the transport sends it from its start and closes it.

#include <cstdint>
#include <memory>
#include <string_view>

namespace avk::server {

// A response body too large to hold in memory (an export written to a temporary file, unlinked
// already): the transport sends it from its start and closes it. Owns the descriptor.
class BodyFile {
 public:
  explicit BodyFile(int fd) : fd_(fd) {}
  ~BodyFile();
  BodyFile(const BodyFile&) = delete;
  BodyFile& operator=(const BodyFile&) = delete;
  int fd() const { return fd_; }
  // Appends; throws std::runtime_error when the file cannot take it (a full disk).
  void write(std::string_view bytes);
  // The size as written; throws std::runtime_error when the descriptor cannot be read.
  std::uint64_t size() const;

 private:
  int fd_;
};

// A new temporary file for a BodyFile, already unlinked (nothing is left behind if the process
// dies), in std::filesystem::temp_directory_path() ($TMPDIR). Throws std::runtime_error naming
// the folder when none can be made.
std::shared_ptr<BodyFile> temporary_body_file();

}  // namespace avk::server
