#pragma once
// The dashboard's optional map background: raster tiles the operator provides offline (a station
// on the shore may have no internet), given to `avk serve --tiles PATH`. PATH is a folder of
// slippy-map tiles `{z}/{x}/{y}.png` (or .jpg, .jpeg, .webp) in the XYZ scheme (Web Mercator, y
// from the north), or an MBTiles file. Either is served the same way: tiles by XYZ coordinates
// with their media type, and what the page needs to choose them (zoom levels, bounds).
//
// The tiles are requests from outside reading the station's disk, so a folder is confined: every
// path is resolved (links followed) and must stay within the folder's own resolved path, so a
// link to /etc/passwd or to the station's token file serves nothing; a link within the folder
// (one tile standing for another) is followed. And nothing is served that is not an image: the
// media type is the image's signature, never the file's extension.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "app/result.hpp"

namespace avk::app::tiles {

// The zoom levels a tile address may name (z 0..24, x and y below 2^z).
inline constexpr int kMaxTileZoom = 24;

struct MapTileInfo {
  std::string source;  // "folder" or "mbtiles"
  std::string format;  // "png", "jpg" or "webp": what most (an MBTiles file: all) tiles are
  int min_zoom = 0;
  int max_zoom = 0;
  // West, south, east, north in degrees: MBTiles' `bounds`, or the extent of a folder's tiles at
  // its highest zoom; none when not known.
  std::optional<std::array<double, 4>> bounds_deg;
  std::string name;  // MBTiles' `name`, else the folder's name
};

struct MapTile {
  std::string bytes;
  std::string media_type;  // image/png, image/jpeg, image/webp
};

class MapTiles {
 public:
  virtual ~MapTiles() = default;
  virtual const MapTileInfo& info() const = 0;
  // The tile at XYZ (z, x, y). invalid_argument (field "z", "x" or "y") for an address outside
  // the scheme; not_found, saying why, when the source has no such tile or holds one it does not
  // serve: a file that is no PNG, JPEG or WebP image by its signature, or (a folder) a link that
  // leaves the folder. Safe to call from many threads.
  Result<MapTile> tile(int z, std::int64_t x, std::int64_t y) const;

 protected:
  // The tile at an address in the scheme, or not_found as above.
  virtual Result<MapTile> find(int z, std::int64_t x, std::int64_t y) const = 0;
};

// Opens a folder or an MBTiles file, checking it holds raster tiles: invalid_argument (field
// "tiles") naming the path and what is wrong otherwise (missing, unreadable, not MBTiles, vector
// tiles, no tiles at all).
Result<std::shared_ptr<const MapTiles>> open_map_tiles(const std::string& path);

// The media type of an image from its first bytes (PNG, JPEG, WebP signatures); empty if none.
std::string sniff_image_type(const std::string& bytes);

}  // namespace avk::app::tiles
