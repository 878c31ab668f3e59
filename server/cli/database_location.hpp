#pragma once
// Whether this process can keep a database (and its token, WAL and shared-memory files) where it
// was asked to, checked before anything is written, so that a start that cannot says why.

#include <string>

namespace avk::server {

// Throws std::runtime_error naming the folder (or the database file), its owner and mode, the uid
// this process runs as and what to do (chown, or running as the owner) when the folder is missing,
// is not a folder, or cannot be written by this process, or when the database file exists and
// cannot be written. A Docker bind mount owned by root is the usual case: the image runs as an
// unprivileged user.
void check_database_location(const std::string& db_path);

}  // namespace avk::server
