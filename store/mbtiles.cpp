#include "store/mbtiles.hpp"

#include <sqlite3.h>

#include <filesystem>

namespace avk::store {

namespace {

// The wrapper opens read-write-create; the file is the operator's and must never be created or
// changed. A URI with mode=ro asks SQLite for read-only where the library takes URIs in every open
// (SQLITE_USE_URI, as Debian builds it); query_only then refuses any write whichever way it was
// opened, and a missing file is refused before SQLite could create it.
std::string read_only_name(const std::string& path) {
  if (!sqlite3_compileoption_used("USE_URI")) return path;
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%')
      uri += "%25";
    else if (c == '?')
      uri += "%3f";
    else if (c == '#')
      uri += "%23";
    else
      uri += c;
  }
  uri += "?mode=ro";
  return uri;
}

Connection open_read_only(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw StoreError("cannot open the MBTiles file '" + path + "': no such file");
  try {
    return Connection(read_only_name(path));
  } catch (const StoreError& e) {
    throw StoreError("cannot open the MBTiles file '" + path + "': " + e.what(), e.engine_code());
  }
}

// SQLite reads a file's header only at the first statement: a file that is not a database fails
// here, so this is where it is named.
bool has_relation(const Connection& db, const std::string& path, const char* name) {
  try {
    auto s =
        db.prepare("SELECT 1 FROM sqlite_master WHERE name = ?1 AND type IN ('table', 'view')");
    s.bind(1, name);
    return s.step();
  } catch (const StoreError& e) {
    throw StoreError(
        "'" + path + "' is not an MBTiles file (not an SQLite database: " + e.what() + ")",
        e.engine_code());
  }
}

Statement checked_tiles(const Connection& db, const std::string& path) {
  if (!has_relation(db, path, "tiles"))
    throw StoreError("'" + path +
                     "' is not an MBTiles file: it is an SQLite database without a `tiles` table");
  return db.prepare(
      "SELECT tile_data FROM tiles WHERE zoom_level = ?1 AND tile_column = ?2 AND tile_row = ?3");
}

std::string blob_string(const Statement& s, int column) {
  const auto bytes = s.column_blob(column);
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace

// The connection is made before tile_ (member order), and tile_ is prepared after the check.
MbtilesReader::MbtilesReader(const std::string& path)
    : path_(path), db_(open_read_only(path)), tile_(checked_tiles(db_, path)) {
  db_.exec("PRAGMA query_only = ON");
}

std::map<std::string, std::string> MbtilesReader::metadata() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::string> out;
  if (!has_relation(db_, path_, "metadata")) return out;
  auto s = db_.prepare("SELECT name, value FROM metadata");
  while (s.step())
    if (!s.is_null(0) && !s.is_null(1)) out[s.column_text(0)] = s.column_text(1);
  return out;
}

std::optional<std::pair<int, int>> MbtilesReader::zoom_range() const {
  std::lock_guard lock(mutex_);
  auto s = db_.prepare("SELECT MIN(zoom_level), MAX(zoom_level) FROM tiles");
  if (!s.step() || s.is_null(0) || s.is_null(1)) return std::nullopt;
  return std::pair{static_cast<int>(s.column_int64(0)), static_cast<int>(s.column_int64(1))};
}

std::optional<std::string> MbtilesReader::tile(int zoom, std::int64_t column,
                                               std::int64_t row) const {
  std::lock_guard lock(mutex_);
  tile_.reset();
  tile_.bind(1, zoom).bind(2, column).bind(3, row);
  std::optional<std::string> out;
  if (tile_.step() && !tile_.is_null(0)) out = blob_string(tile_, 0);
  tile_.reset();
  return out;
}

std::optional<std::string> MbtilesReader::any_tile() const {
  std::lock_guard lock(mutex_);
  auto s = db_.prepare("SELECT tile_data FROM tiles WHERE tile_data IS NOT NULL LIMIT 1");
  if (!s.step()) return std::nullopt;
  return blob_string(s, 0);
}

}  // namespace avk::store
