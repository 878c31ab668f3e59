#include "server/body_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace avk::server {

BodyFile::~BodyFile() {
  if (fd_ >= 0) ::close(fd_);
}

void BodyFile::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const auto n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error(std::string("cannot write a temporary response file: ") +
                               std::strerror(errno));
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

std::uint64_t BodyFile::size() const {
  struct stat st {};
  if (::fstat(fd_, &st) != 0)
    throw std::runtime_error(std::string("cannot read a temporary response file: ") +
                             std::strerror(errno));
  return static_cast<std::uint64_t>(st.st_size);
}

std::shared_ptr<BodyFile> temporary_body_file() {
  const std::string dir = std::filesystem::temp_directory_path().string();
  // A file with no name at all where the file system allows it; else a named one unlinked at once.
  int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) {
    std::string name = dir + "/avk-response-XXXXXX";
    fd = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd >= 0) ::unlink(name.c_str());
  }
  if (fd < 0)
    throw std::runtime_error("cannot make a temporary response file in " + dir + ": " +
                             std::strerror(errno));
  return std::make_shared<BodyFile>(fd);
}

}  // namespace avk::server
