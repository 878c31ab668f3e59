#include "server/cli/database_location.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace avk::server {

namespace {

namespace fs = std::filesystem;

std::string mode_text(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// Whether this process (its effective uid and groups, as the kernel will judge it) may `mode` it.
bool may(const fs::path& path, int mode) {
  return ::faccessat(AT_FDCWD, path.c_str(), mode, AT_EACCESS) == 0;
}

// What an operator needs to fix it: who owns the path, who this process is, and the two ways out.
[[noreturn]] void cannot_write(const std::string& what, const fs::path& path,
                               const struct stat& st) {
  const std::string uid = std::to_string(::geteuid());
  const std::string owner = std::to_string(st.st_uid);
  throw std::runtime_error("cannot write " + what + " " + path.string() + ": it is owned by uid " +
                           owner + " (gid " + std::to_string(st.st_gid) + ", mode " +
                           mode_text(st.st_mode) + ") and avk runs as uid " + uid + " (gid " +
                           std::to_string(::getegid()) + "). Give it to uid " + uid + " (chown " +
                           uid + " " + path.string() + "; for a Docker bind mount, chown " + uid +
                           " the host folder, on the host) or run avk as its owner, uid " + owner +
                           " (docker run --user " + owner + ")");
}

}  // namespace

void check_database_location(const std::string& db_path) {
  const fs::path db(db_path);
  const fs::path folder = db.has_parent_path() ? db.parent_path() : fs::path(".");
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0)
    throw std::runtime_error("the database folder " + folder.string() +
                             " cannot be used: " + std::strerror(errno));
  if (!S_ISDIR(st.st_mode))
    throw std::runtime_error("the database folder " + folder.string() + " is not a folder");
  // The token file, SQLite's journal files and a new database are created in the folder.
  if (!may(folder, W_OK | X_OK)) cannot_write("in the database folder", folder, st);
  if (::stat(db.c_str(), &st) == 0 && !may(db, W_OK)) cannot_write("the database", db, st);
}

}  // namespace avk::server
