#include "app/tiles/map_tiles.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <vector>

#include "store/mbtiles.hpp"

namespace avk::app::tiles {

namespace {

namespace fs = std::filesystem;

// The raster formats a browser draws, with the file extensions a tile folder may use.
struct ImageFormat {
  const char* format;
  const char* extension;
  const char* media_type;
};
constexpr ImageFormat kFormats[] = {{"png", "png", "image/png"},
                                    {"jpg", "jpg", "image/jpeg"},
                                    {"jpg", "jpeg", "image/jpeg"},
                                    {"webp", "webp", "image/webp"}};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A directory or file name that is a whole number (a zoom level, a column, a row); at most 8
// digits, which is more than 2^24.
std::optional<std::int64_t> whole_name(const std::string& name) {
  if (name.empty() || name.size() > 8) return std::nullopt;
  std::int64_t v = 0;
  for (const char c : name) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + (c - '0');
  }
  return v;
}

// Web Mercator (the XYZ scheme): the longitude of a tile column's west edge and the latitude of a
// tile row's north edge at zoom z.
double tile_lon_deg(double x, int z) {
  return x / std::ldexp(1.0, z) * 360.0 - 180.0;
}
double tile_lat_deg(double y, int z) {
  const double n = std::numbers::pi * (1.0 - 2.0 * y / std::ldexp(1.0, z));
  return std::atan(std::sinh(n)) * 180.0 / std::numbers::pi;
}

std::string tile_name(int z, std::int64_t x, std::int64_t y) {
  std::string s = std::to_string(z);
  s += "/";
  s += std::to_string(x);
  s += "/";
  s += std::to_string(y);
  return s;
}

Error no_tile(int z, std::int64_t x, std::int64_t y) {
  return not_found("no map tile " + tile_name(z, x, y) + " in the station's tiles");
}

// A tile's bytes with the media type of their signature; not_found when they are no image a
// browser draws (whatever the file's extension or the MBTiles format says).
Result<MapTile> tile_of(std::string bytes, int z, std::int64_t x, std::int64_t y) {
  std::string type = sniff_image_type(bytes);
  if (type.empty())
    return not_found("map tile " + tile_name(z, x, y) +
                     " is not a PNG, JPEG or WebP image (by its signature); it is not served");
  return MapTile{std::move(bytes), std::move(type)};
}

// Whether a resolved path lies within the resolved root, compared by whole components
// (/tiles2 is not within /tiles).
bool inside(const fs::path& root, const fs::path& resolved) {
  return std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end()).first ==
         root.end();
}

// Whether a directory entry under the root stays in it: an entry that is not a link does (its
// directory does); a link does when what it resolves to does.
bool stays_inside(const fs::path& root, const fs::directory_entry& e) {
  std::error_code ec;
  if (!e.is_symlink(ec) && !ec) return true;
  const fs::path resolved = fs::canonical(e.path(), ec);
  return !ec && inside(root, resolved);
}

// ---------------------------------------------------------------- a folder {z}/{x}/{y}.ext

class FolderTiles final : public MapTiles {
 public:
  FolderTiles(fs::path root, MapTileInfo info) : root_(std::move(root)), info_(std::move(info)) {
    // The folder's own format first: most lookups then find the tile at the first try.
    for (const auto& f : kFormats)
      if (info_.format == f.format) extensions_.push_back(f.extension);
    for (const auto& f : kFormats)
      if (info_.format != f.format) extensions_.push_back(f.extension);
  }
  const MapTileInfo& info() const override { return info_; }

 protected:
  // The path is made of the three parsed integers only, and what it resolves to (links followed)
  // must lie within the folder: neither a request nor a link in the folder reaches a file
  // outside it. The file read is the resolved one.
  Result<MapTile> find(int z, std::int64_t x, std::int64_t y) const override {
    const fs::path dir = root_ / std::to_string(z) / std::to_string(x);
    std::optional<Error> refused;
    for (const char* ext : extensions_) {
      const fs::path file = dir / (std::to_string(y) + "." + ext);
      std::error_code ec;
      const fs::path resolved = fs::canonical(file, ec);
      if (ec) continue;  // no such file (or a dangling link)
      if (!inside(root_, resolved)) {
        if (!refused)
          refused = not_found("map tile " + tile_name(z, x, y) +
                              " is a link that leaves the tile folder; it is not served");
        continue;
      }
      if (!fs::is_regular_file(resolved, ec)) continue;
      std::ifstream in(resolved, std::ios::binary);
      if (!in) continue;
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      auto t = tile_of(std::move(bytes), z, x, y);
      if (t) return t;
      if (!refused) refused = t.error();
    }
    if (refused) return *refused;
    return no_tile(z, x, y);
  }

 private:
  fs::path root_;
  MapTileInfo info_;
  std::vector<const char*> extensions_;
};

// The entries of a directory (none when it cannot be read); at most `limit` of them.
std::vector<fs::directory_entry> entries(const fs::path& dir, std::size_t limit, bool& cut) {
  std::vector<fs::directory_entry> out;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
    if (out.size() == limit) {
      cut = true;
      break;
    }
    out.push_back(*it);
  }
  return out;
}

// A tile file's row and format: "12.png" -> (12, "png"); none for a link that leaves the root.
std::optional<std::pair<std::int64_t, std::string>> tile_file(const fs::path& root,
                                                              const fs::directory_entry& e) {
  std::error_code ec;
  if (!e.is_regular_file(ec) || !stays_inside(root, e)) return std::nullopt;
  const std::string ext = lower(e.path().extension().string());
  for (const auto& f : kFormats) {
    if (ext != std::string(".") + f.extension) continue;
    const auto row = whole_name(e.path().stem().string());
    if (row) return std::pair{*row, std::string(f.format)};
  }
  return std::nullopt;
}

Result<std::shared_ptr<const MapTiles>> open_folder(const std::string& path) {
  std::error_code ec;
  const fs::path root = fs::canonical(path, ec);
  if (ec)
    return invalid_argument("tiles", "cannot read the tile folder '" + path + "': " + ec.message());
  // Scanning is bounded: a folder of a whole region holds millions of tiles.
  constexpr std::size_t kScanLimit = 200000;
  bool cut = false;
  std::map<int, fs::path> levels;
  for (const auto& e : entries(root, 1000, cut)) {
    const auto z = whole_name(e.path().filename().string());
    if (z && *z <= kMaxTileZoom && e.is_directory(ec) && stays_inside(root, e))
      levels[static_cast<int>(*z)] = e.path();
  }
  // A level counts when it holds a tile; the format is the first tile's.
  std::string format;
  std::vector<int> zooms;
  for (const auto& [z, dir] : levels) {
    bool found = false;
    for (const auto& column : entries(dir, kScanLimit, cut)) {
      if (!whole_name(column.path().filename().string()) || !column.is_directory(ec) ||
          !stays_inside(root, column))
        continue;
      for (const auto& file : entries(column.path(), kScanLimit, cut)) {
        if (const auto t = tile_file(root, file)) {
          if (format.empty()) format = t->second;
          found = true;
          break;
        }
      }
      if (found) break;
    }
    if (found) zooms.push_back(z);
  }
  if (zooms.empty())
    return invalid_argument("tiles", "the tile folder '" + path +
                                         "' holds no tiles: expected {z}/{x}/{y}.png (or .jpg, "
                                         ".jpeg, .webp) in the XYZ scheme, z from 0 to 24");
  MapTileInfo info;
  info.source = "folder";
  info.format = format;
  info.min_zoom = zooms.front();
  info.max_zoom = zooms.back();
  info.name = root.filename().string();
  // The extent of the finest level's tiles, unless the level is too large to list.
  cut = false;
  std::int64_t x0 = std::numeric_limits<std::int64_t>::max(), x1 = -1;
  std::int64_t y0 = std::numeric_limits<std::int64_t>::max(), y1 = -1;
  const std::int64_t n = std::int64_t{1} << info.max_zoom;
  for (const auto& column : entries(levels.at(info.max_zoom), kScanLimit, cut)) {
    const auto x = whole_name(column.path().filename().string());
    if (!x || *x >= n || !column.is_directory(ec) || !stays_inside(root, column)) continue;
    for (const auto& file : entries(column.path(), kScanLimit, cut)) {
      const auto t = tile_file(root, file);
      if (!t || t->first >= n) continue;
      x0 = std::min(x0, *x);
      x1 = std::max(x1, *x);
      y0 = std::min(y0, t->first);
      y1 = std::max(y1, t->first);
    }
  }
  if (!cut && x1 >= 0)
    info.bounds_deg =
        std::array<double, 4>{tile_lon_deg(static_cast<double>(x0), info.max_zoom),
                              tile_lat_deg(static_cast<double>(y1 + 1), info.max_zoom),
                              tile_lon_deg(static_cast<double>(x1 + 1), info.max_zoom),
                              tile_lat_deg(static_cast<double>(y0), info.max_zoom)};
  return std::shared_ptr<const MapTiles>(std::make_shared<FolderTiles>(root, std::move(info)));
}

// ---------------------------------------------------------------- an MBTiles file

class MbtilesTiles final : public MapTiles {
 public:
  MbtilesTiles(std::unique_ptr<store::MbtilesReader> reader, MapTileInfo info)
      : reader_(std::move(reader)), info_(std::move(info)) {}
  const MapTileInfo& info() const override { return info_; }

 protected:
  // MBTiles stores rows in the TMS scheme, counted from the south (spec 1.3).
  Result<MapTile> find(int z, std::int64_t x, std::int64_t y) const override {
    const std::int64_t row = (std::int64_t{1} << z) - 1 - y;
    auto bytes = reader_->tile(z, x, row);
    if (!bytes) return no_tile(z, x, y);
    return tile_of(std::move(*bytes), z, x, y);
  }

 private:
  std::unique_ptr<store::MbtilesReader> reader_;
  MapTileInfo info_;
};

std::optional<int> zoom_of(const std::map<std::string, std::string>& meta, const char* key) {
  const auto it = meta.find(key);
  if (it == meta.end()) return std::nullopt;
  const auto v = whole_name(it->second);
  if (!v || *v > kMaxTileZoom) return std::nullopt;
  return static_cast<int>(*v);
}

// "west,south,east,north" in degrees; none unless it is a proper box on the earth.
std::optional<std::array<double, 4>> bounds_of(const std::map<std::string, std::string>& meta) {
  const auto it = meta.find("bounds");
  if (it == meta.end()) return std::nullopt;
  std::array<double, 4> b{};
  std::istringstream in(it->second);
  for (std::size_t i = 0; i < 4; ++i) {
    std::string part;
    if (!std::getline(in, part, i < 3 ? ',' : '\n')) return std::nullopt;
    try {
      std::size_t used = 0;
      b[i] = std::stod(part, &used);
      if (part.find_first_not_of(" \t", used) != std::string::npos) return std::nullopt;
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  const bool ok =
      b[0] >= -180 && b[2] <= 180 && b[0] < b[2] && b[1] >= -90 && b[3] <= 90 && b[1] < b[3];
  if (!ok) return std::nullopt;
  return b;
}

Result<std::shared_ptr<const MapTiles>> open_mbtiles(const std::string& path) {
  std::unique_ptr<store::MbtilesReader> reader;
  std::map<std::string, std::string> meta;
  std::optional<std::pair<int, int>> range;
  std::optional<std::string> sample;
  try {
    reader = std::make_unique<store::MbtilesReader>(path);
    meta = reader->metadata();
    range = reader->zoom_range();
    if (range) sample = reader->any_tile();
  } catch (const store::StoreError& e) {
    return invalid_argument("tiles", e.what());
  }
  if (!range) return invalid_argument("tiles", "the MBTiles file '" + path + "' holds no tiles");
  MapTileInfo info;
  info.source = "mbtiles";
  const auto declared = meta.find("format");
  std::string format = declared == meta.end() ? std::string() : lower(declared->second);
  if (format == "jpeg") format = "jpg";
  if (format.empty() && sample) {
    const std::string type = sniff_image_type(*sample);
    for (const auto& f : kFormats)
      if (type == f.media_type) format = f.format;
  }
  if (format == "pbf" || format == "mvt")
    return invalid_argument("tiles", "the MBTiles file '" + path + "' holds vector tiles (format " +
                                         format +
                                         "); the map background needs raster tiles (png, jpg "
                                         "or webp)");
  if (format != "png" && format != "jpg" && format != "webp")
    return invalid_argument("tiles",
                            "the MBTiles file '" + path + "' holds tiles of format '" +
                                (format.empty() ? std::string("unknown") : format) +
                                "'; the map background needs raster tiles (png, jpg or webp)");
  info.format = format;
  // The spec's minzoom/maxzoom when they make sense, else what the tiles table holds.
  const auto min_zoom = zoom_of(meta, "minzoom");
  const auto max_zoom = zoom_of(meta, "maxzoom");
  const bool declared_zooms = min_zoom && max_zoom && *min_zoom <= *max_zoom;
  info.min_zoom = declared_zooms ? *min_zoom : std::clamp(range->first, 0, kMaxTileZoom);
  info.max_zoom = declared_zooms ? *max_zoom : std::clamp(range->second, 0, kMaxTileZoom);
  info.bounds_deg = bounds_of(meta);
  const auto name = meta.find("name");
  info.name = name != meta.end() ? name->second : fs::path(path).stem().string();
  return std::shared_ptr<const MapTiles>(
      std::make_shared<MbtilesTiles>(std::move(reader), std::move(info)));
}

}  // namespace

std::string sniff_image_type(const std::string& b) {
  if (b.size() >= 8 && b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return "image/png";
  if (b.size() >= 3 && b.compare(0, 3, "\xff\xd8\xff") == 0) return "image/jpeg";
  if (b.size() >= 12 && b.compare(0, 4, "RIFF") == 0 && b.compare(8, 4, "WEBP") == 0)
    return "image/webp";
  return "";
}

Result<MapTile> MapTiles::tile(int z, std::int64_t x, std::int64_t y) const {
  if (z < 0 || z > kMaxTileZoom)
    return invalid_argument("z", "must be a zoom level from 0 to " + std::to_string(kMaxTileZoom) +
                                     ", got " + std::to_string(z));
  const std::int64_t n = std::int64_t{1} << z;
  const std::string within =
      "must be from 0 to " + std::to_string(n - 1) + " at zoom " + std::to_string(z) + ", got ";
  if (x < 0 || x >= n) return invalid_argument("x", within + std::to_string(x));
  if (y < 0 || y >= n) return invalid_argument("y", within + std::to_string(y));
  return find(z, x, y);
}

Result<std::shared_ptr<const MapTiles>> open_map_tiles(const std::string& path) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    return invalid_argument(
        "tiles", "'" + path + "' does not exist (give a tile folder or an " + "MBTiles file)");
  if (fs::is_directory(status)) return open_folder(path);
  if (!fs::is_regular_file(status))
    return invalid_argument("tiles", "'" + path + "' is neither a tile folder nor an MBTiles file");
  // Unreadable files are named here, not as SQLite's "unable to open database file".
  if (!std::ifstream(path, std::ios::binary))
    return invalid_argument("tiles", "cannot read '" + path + "' (permissions?)");
  return open_mbtiles(path);
}

}  // namespace avk::app::tiles
