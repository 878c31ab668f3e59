// The map background's tile sources (`avk serve --tiles`): a folder of {z}/{x}/{y} images and an
// MBTiles file answer the same XYZ address with the same tile; what the page needs (zoom levels,
// bounds, format) is read from either; anything else is refused naming the path.
#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>

#include "app/tiles/map_tiles.hpp"
#include "store/sqlite.hpp"
#include "support/temp_db.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using avk::app::ErrorCode;
using avk::app::tiles::open_map_tiles;

const std::string kPng = std::string("\x89PNG\r\n\x1a\n", 8) + "png-body";
const std::string kJpeg = std::string("\xff\xd8\xff\xe0", 4) + "jpeg-body";

using avk::testing::TempDir;

// Web Mercator, as the page and every slippy map compute it.
double lon_of(double x, int z) {
  return x / std::ldexp(1.0, z) * 360.0 - 180.0;
}
double lat_of(double y, int z) {
  return std::atan(std::sinh(M_PI * (1.0 - 2.0 * y / std::ldexp(1.0, z)))) * 180.0 / M_PI;
}

TEST(MapTiles, AFolderAnswersItsTilesWithTheirMediaType) {
  TempDir dir("avk_tiles_folder");
  dir.write("16/19808/24184.png", kPng);
  dir.write("16/19809/24185.png", kPng);
  dir.write("15/9904/12092.png", kPng);
  // A tile of another format in the same folder, and files that are not tiles.
  dir.write("16/19809/24184.jpg", kJpeg);
  dir.write("16/19808/readme.txt", "not a tile");
  dir.write("notes/1/1.png", kPng);
  dir.write("30/0/0.png", kPng);  // beyond zoom 24: not a level
  const auto tiles = open_map_tiles(dir.path().string());
  ASSERT_TRUE(tiles) << tiles.error().message;
  const auto& info = (*tiles)->info();
  EXPECT_EQ(info.source, "folder");
  EXPECT_EQ(info.format, "png");
  EXPECT_EQ(info.min_zoom, 15);
  EXPECT_EQ(info.max_zoom, 16);
  // The extent of the finest level: columns 19808-19809, rows 24184-24185.
  ASSERT_TRUE(info.bounds_deg);
  EXPECT_NEAR((*info.bounds_deg)[0], lon_of(19808, 16), 1e-9);
  EXPECT_NEAR((*info.bounds_deg)[1], lat_of(24186, 16), 1e-9);
  EXPECT_NEAR((*info.bounds_deg)[2], lon_of(19810, 16), 1e-9);
  EXPECT_NEAR((*info.bounds_deg)[3], lat_of(24184, 16), 1e-9);

  const auto png = (*tiles)->tile(16, 19808, 24184);
  ASSERT_TRUE(png) << png.error().message;
  EXPECT_EQ(png->bytes, kPng);
  EXPECT_EQ(png->media_type, "image/png");
  const auto jpg = (*tiles)->tile(16, 19809, 24184);
  ASSERT_TRUE(jpg) << jpg.error().message;
  EXPECT_EQ(jpg->bytes, kJpeg);
  EXPECT_EQ(jpg->media_type, "image/jpeg");

  const auto missing = (*tiles)->tile(16, 19808, 24186);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::not_found);
  EXPECT_NE(missing.error().message.find("16/19808/24186"), std::string::npos);
}

TEST(MapTiles, AnAddressOutsideTheSchemeIsInvalidNamingTheCoordinate) {
  TempDir dir("avk_tiles_range");
  dir.write("0/0/0.png", kPng);
  const auto tiles = open_map_tiles(dir.path().string());
  ASSERT_TRUE(tiles) << tiles.error().message;
  struct Case {
    int z;
    std::int64_t x, y;
    const char* field;
  };
  for (const Case& c :
       {Case{-1, 0, 0, "z"}, Case{25, 0, 0, "z"}, Case{0, 1, 0, "x"}, Case{0, 0, 1, "y"},
        Case{3, -1, 0, "x"}, Case{3, 0, 8, "y"}, Case{24, 1 << 24, 0, "x"}}) {
    const auto t = (*tiles)->tile(c.z, c.x, c.y);
    ASSERT_FALSE(t) << c.z << "/" << c.x << "/" << c.y;
    EXPECT_EQ(t.error().code, ErrorCode::invalid_argument);
    EXPECT_EQ(t.error().field, c.field);
  }
  // The highest address of the highest zoom is a valid one (just not there).
  const auto last = (*tiles)->tile(24, (1 << 24) - 1, (1 << 24) - 1);
  ASSERT_FALSE(last);
  EXPECT_EQ(last.error().code, ErrorCode::not_found);
}

void make_mbtiles(const std::string& path, const std::string& format, bool with_zooms = true) {
  avk::store::Connection db(path);
  db.exec("CREATE TABLE metadata (name TEXT, value TEXT)");
  db.exec(
      "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
      "tile_data BLOB)");
  auto meta = db.prepare("INSERT INTO metadata VALUES (?1, ?2)");
  const auto put_meta = [&](const char* k, const std::string& v) {
    meta.reset();
    meta.bind(1, k).bind(2, v);
    meta.run();
  };
  put_meta("name", "Charles River");
  if (!format.empty()) put_meta("format", format);
  put_meta("bounds", "-71.1,42.35,-71.08,42.36");
  if (with_zooms) {
    put_meta("minzoom", "12");
    put_meta("maxzoom", "18");
  }
  auto tile = db.prepare("INSERT INTO tiles VALUES (?1, ?2, ?3, ?4)");
  const auto put_tile = [&](int z, int x, int y_xyz, const std::string& bytes) {
    tile.reset();
    // MBTiles rows count from the south (TMS).
    tile.bind(1, z).bind(2, x).bind(3, (1 << z) - 1 - y_xyz);
    tile.bind_blob(4, {reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()});
    tile.run();
  };
  put_tile(16, 19808, 24184, kPng);
  put_tile(14, 4952, 6046, kPng);
}

TEST(MapTiles, AnMbtilesFileAnswersByXyzAddress) {
  avk::testing::TempDb db("avk_tiles_mbtiles");
  make_mbtiles(db.path(), "png");
  const auto tiles = open_map_tiles(db.path());
  ASSERT_TRUE(tiles) << tiles.error().message;
  const auto& info = (*tiles)->info();
  EXPECT_EQ(info.source, "mbtiles");
  EXPECT_EQ(info.format, "png");
  EXPECT_EQ(info.name, "Charles River");
  EXPECT_EQ(info.min_zoom, 12);
  EXPECT_EQ(info.max_zoom, 18);
  ASSERT_TRUE(info.bounds_deg);
  EXPECT_DOUBLE_EQ((*info.bounds_deg)[0], -71.1);
  EXPECT_DOUBLE_EQ((*info.bounds_deg)[1], 42.35);
  EXPECT_DOUBLE_EQ((*info.bounds_deg)[2], -71.08);
  EXPECT_DOUBLE_EQ((*info.bounds_deg)[3], 42.36);
  const auto t = (*tiles)->tile(16, 19808, 24184);
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(t->bytes, kPng);
  EXPECT_EQ(t->media_type, "image/png");
  // The stored (TMS) row is not an XYZ address of the tile.
  EXPECT_FALSE((*tiles)->tile(16, 19808, (1 << 16) - 1 - 24184));
}

TEST(MapTiles, WithoutZoomsOrFormatInTheMetadataTheTilesTell) {
  avk::testing::TempDb db("avk_tiles_mbtiles_bare");
  make_mbtiles(db.path(), "", false);
  const auto tiles = open_map_tiles(db.path());
  ASSERT_TRUE(tiles) << tiles.error().message;
  EXPECT_EQ((*tiles)->info().format, "png");
  EXPECT_EQ((*tiles)->info().min_zoom, 14);
  EXPECT_EQ((*tiles)->info().max_zoom, 16);
}

// What `avk serve --tiles` says: the path and what is wrong with it.
void expect_refused(const std::string& path, const std::string& words) {
  const auto tiles = open_map_tiles(path);
  ASSERT_FALSE(tiles) << path;
  EXPECT_EQ(tiles.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(tiles.error().field, "tiles");
  EXPECT_NE(tiles.error().message.find(path), std::string::npos) << tiles.error().message;
  EXPECT_NE(tiles.error().message.find(words), std::string::npos) << tiles.error().message;
}

TEST(MapTiles, WhatIsNotATileSourceIsRefusedNamingThePath) {
  TempDir dir("avk_tiles_bad");
  expect_refused((dir.path() / "nowhere").string(), "does not exist");
  expect_refused(dir.path().string(), "holds no tiles");
  dir.write("text.mbtiles", "just text, no database\n");
  expect_refused((dir.path() / "text.mbtiles").string(), "not an MBTiles file");
  {
    avk::store::Connection other((dir.path() / "station.db").string());
    other.exec("CREATE TABLE missions (id INTEGER)");
  }
  expect_refused((dir.path() / "station.db").string(), "not an MBTiles file");
  avk::testing::TempDb vector("avk_tiles_vector");
  make_mbtiles(vector.path(), "pbf");
  expect_refused(vector.path(), "vector tiles");
  avk::testing::TempDb empty("avk_tiles_empty");
  {
    avk::store::Connection c(empty.path());
    c.exec(
        "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
        "tile_data BLOB)");
  }
  expect_refused(empty.path(), "holds no tiles");
}

// Regression: `ln -s /etc/passwd tiles/1/0/0.png` served /etc/passwd as image/png, and a link to
// the station's token file served the token. Links are resolved and must stay in the folder;
// one within the folder is followed.
TEST(MapTiles, ALinkThatLeavesTheFolderServesNothing) {
  TempDir base("avk_tiles_links");
  base.write("tiles/1/0/0.png", kPng);
  base.write("station.db.token", "0123456789abcdef-secret-token\n");
  base.write("secret.png", kPng + "SECRET");
  base.write("outside/0/0.png", kPng + "SECRET");
  const fs::path tiles = base.path() / "tiles";
  fs::create_directories(tiles / "1/1");
  fs::create_symlink(base.path() / "station.db.token", tiles / "1/1/0.png");
  fs::create_symlink("../../../secret.png", tiles / "1/1/1.png");  // relative, still outside
  fs::create_symlink("/etc/passwd", tiles / "1/0/1.png");
  fs::create_symlink(base.path() / "outside", tiles / "4");  // a whole level outside
  fs::create_directories(tiles / "3/0");
  fs::create_symlink("../../1/0/0.png", tiles / "3/0/0.png");  // within the folder
  // A folder reached by a link of its own is confined to where the link leads.
  fs::create_symlink(tiles, base.path() / "tiles-link");

  for (const fs::path& root : {tiles, base.path() / "tiles-link"}) {
    const auto opened = open_map_tiles(root.string());
    ASSERT_TRUE(opened) << opened.error().message;
    const auto& t = **opened;
    EXPECT_EQ(t.info().max_zoom, 3) << "the level outside is not one of the folder's";
    for (const auto& [z, x, y] :
         {std::tuple{1, 1, 0}, std::tuple{1, 1, 1}, std::tuple{1, 0, 1}, std::tuple{4, 0, 0}}) {
      const auto r = t.tile(z, x, y);
      ASSERT_FALSE(r) << z << "/" << x << "/" << y << " served " << r->bytes;
      EXPECT_EQ(r.error().code, ErrorCode::not_found);
      EXPECT_NE(r.error().message.find("leaves the tile folder"), std::string::npos)
          << r.error().message;
    }
    const auto within = t.tile(3, 0, 0);
    ASSERT_TRUE(within) << within.error().message;
    EXPECT_EQ(within->bytes, kPng);
  }
}

// Regression: a file with no image signature was served with the type of its extension.
TEST(MapTiles, AFileThatIsNoImageIsNotServed) {
  TempDir dir("avk_tiles_not_images");
  dir.write("1/0/0.png", kPng);
  dir.write("1/0/1.png", "root:x:0:0:root:/root:/bin/bash\n");
  dir.write("1/1/0.jpg", "GIF89a not a format the page draws");
  dir.write("1/1/1.webp", "");
  // A JPEG named .png is served as what it is.
  dir.write("2/0/2.png", kJpeg);
  const auto tiles = open_map_tiles(dir.path().string());
  ASSERT_TRUE(tiles) << tiles.error().message;
  for (const auto& [x, y] : {std::pair{0, 1}, std::pair{1, 0}, std::pair{1, 1}}) {
    const auto r = (*tiles)->tile(1, x, y);
    ASSERT_FALSE(r) << x << "/" << y << " served as " << r->media_type;
    EXPECT_EQ(r.error().code, ErrorCode::not_found);
    EXPECT_NE(r.error().message.find("not a PNG, JPEG or WebP image"), std::string::npos)
        << r.error().message;
  }
  const auto jpeg = (*tiles)->tile(2, 0, 2);
  ASSERT_TRUE(jpeg) << jpeg.error().message;
  EXPECT_EQ(jpeg->media_type, "image/jpeg");
}

TEST(MapTiles, AnMbtilesTileThatIsNoImageIsNotServed) {
  avk::testing::TempDb db("avk_tiles_mbtiles_text");
  make_mbtiles(db.path(), "png");
  {
    avk::store::Connection c(db.path());
    auto put = c.prepare("INSERT INTO tiles VALUES (?1, ?2, ?3, ?4)");
    const std::string text = "not an image";
    put.bind(1, 16).bind(2, 19808).bind(3, (1 << 16) - 1 - 24185);
    put.bind_blob(4, {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
    put.run();
  }
  const auto tiles = open_map_tiles(db.path());
  ASSERT_TRUE(tiles) << tiles.error().message;
  const auto r = (*tiles)->tile(16, 19808, 24185);
  ASSERT_FALSE(r) << "served as " << r->media_type;
  EXPECT_NE(r.error().message.find("not a PNG, JPEG or WebP image"), std::string::npos);
}

TEST(MapTiles, ImagesAreToldByTheirSignature) {
  EXPECT_EQ(avk::app::tiles::sniff_image_type(kPng), "image/png");
  EXPECT_EQ(avk::app::tiles::sniff_image_type(kJpeg), "image/jpeg");
  EXPECT_EQ(avk::app::tiles::sniff_image_type(std::string("RIFF\x10\0\0\0WEBPVP8 ", 16)),
            "image/webp");
  EXPECT_EQ(avk::app::tiles::sniff_image_type("GIF89a"), "");
}

}  // namespace
