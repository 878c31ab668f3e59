#pragma once
// An MBTiles file (MBTiles 1.3: an SQLite database with `tiles(zoom_level, tile_column, tile_row,
// tile_data)` and `metadata(name, value)`), read-only: the operator's offline map for the
// dashboard's background (`avk serve --tiles FILE.mbtiles`). Rows are as stored, in the TMS
// scheme (row 0 at the south); turning them into the XYZ scheme of a web map is app/'s business.

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "store/sqlite.hpp"

namespace avk::store {

class MbtilesReader {
 public:
  // Opens the file read-only and checks it is an MBTiles database (a `tiles` table or view).
  // Throws StoreError naming the path when it cannot be opened, is not an SQLite database or has
  // no `tiles`.
  explicit MbtilesReader(const std::string& path);

  // Every name/value of `metadata` (empty when the table is missing: the spec requires it, but a
  // map without it can still be drawn).
  std::map<std::string, std::string> metadata() const;
  // The lowest and highest zoom_level holding a tile; none when `tiles` is empty.
  std::optional<std::pair<int, int>> zoom_range() const;
  // The bytes of one tile, none when the file has no such tile. row is TMS (from the south).
  std::optional<std::string> tile(int zoom, std::int64_t column, std::int64_t row) const;
  // Any one tile's bytes (to tell the image format when `metadata` does not name it).
  std::optional<std::string> any_tile() const;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  // One connection (opened SQLITE_OPEN_NOMUTEX) shared by the server's threads.
  mutable std::mutex mutex_;
  Connection db_;
  mutable Statement tile_;
};

}  // namespace avk::store
