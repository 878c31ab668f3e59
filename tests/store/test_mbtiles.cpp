// The MBTiles reader (the offline map of `avk serve --tiles`): an MBTiles 1.3 file made here with
// SQLite is read back as stored (TMS rows, metadata), and anything that is not one is refused
// with its path named, without the file being created or changed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "store/mbtiles.hpp"
#include "store/sqlite.hpp"
#include "support/temp_db.hpp"

namespace {

namespace fs = std::filesystem;
using avk::store::Connection;
using avk::store::MbtilesReader;
using avk::store::StoreError;

void put_tile(Connection& db, int z, int column, int row, const std::string& bytes) {
  auto s = db.prepare(
      "INSERT INTO tiles (zoom_level, tile_column, tile_row, tile_data) VALUES (?1, ?2, ?3, ?4)");
  s.bind(1, z).bind(2, column).bind(3, row);
  s.bind_blob(4, {reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()});
  s.run();
}

void make_mbtiles(const std::string& path) {
  Connection db(path);
  db.exec("CREATE TABLE metadata (name TEXT, value TEXT)");
  db.exec(
      "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
      "tile_data BLOB)");
  db.exec("CREATE UNIQUE INDEX tile_index ON tiles (zoom_level, tile_column, tile_row)");
  db.exec(
      "INSERT INTO metadata VALUES ('name', 'harbour'), ('format', 'png'), "
      "('bounds', '-71.1,42.35,-71.08,42.36'), ('minzoom', '15'), ('maxzoom', '17')");
  put_tile(db, 16, 19808, 41583, std::string("tile-16", 7));
  put_tile(db, 17, 39616, 83167, std::string("\x89PNG\0x", 6));
  put_tile(db, 15, 9904, 20791, "tile-15");
}

TEST(Mbtiles, ReadsTilesByTheirStoredRowsAndTheMetadata) {
  avk::testing::TempDb db("avk_mbtiles");
  make_mbtiles(db.path());
  const MbtilesReader r(db.path());
  const auto meta = r.metadata();
  EXPECT_EQ(meta.at("name"), "harbour");
  EXPECT_EQ(meta.at("format"), "png");
  EXPECT_EQ(meta.at("bounds"), "-71.1,42.35,-71.08,42.36");
  ASSERT_TRUE(r.zoom_range());
  EXPECT_EQ(r.zoom_range()->first, 15);
  EXPECT_EQ(r.zoom_range()->second, 17);
  EXPECT_EQ(r.tile(16, 19808, 41583), std::string("tile-16"));
  // A blob with a NUL byte comes back whole.
  EXPECT_EQ(r.tile(17, 39616, 83167), std::string("\x89PNG\0x", 6));
  // The row is the stored (TMS) one: the XYZ row of the same tile is another tile.
  EXPECT_FALSE(r.tile(16, 19808, (1 << 16) - 1 - 41583));
  EXPECT_FALSE(r.tile(14, 0, 0));
  // The statement is reused: a miss between hits leaves nothing behind.
  EXPECT_EQ(r.tile(15, 9904, 20791), std::string("tile-15"));
  EXPECT_TRUE(r.any_tile());
}

TEST(Mbtiles, AFileWithoutMetadataOrTilesStillOpens) {
  avk::testing::TempDb db("avk_mbtiles_bare");
  {
    Connection c(db.path());
    c.exec(
        "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
        "tile_data BLOB)");
  }
  const MbtilesReader r(db.path());
  EXPECT_TRUE(r.metadata().empty());
  EXPECT_FALSE(r.zoom_range());
  EXPECT_FALSE(r.any_tile());
}

// The message that reaches the operator names the file.
std::string open_error(const std::string& path) {
  try {
    MbtilesReader r(path);
  } catch (const StoreError& e) {
    return e.what();
  }
  return "";
}

TEST(Mbtiles, AMissingFileIsNamedAndNotCreated) {
  avk::testing::TempDb db("avk_mbtiles_missing");
  const std::string error = open_error(db.path());
  EXPECT_NE(error.find(db.path()), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(db.path())) << "opening for reading created the file";
}

TEST(Mbtiles, AFileThatIsNotSqlIsNamed) {
  avk::testing::TempDb db("avk_mbtiles_text");
  std::ofstream(db.path()) << "these are not the tiles you are looking for\n";
  const std::string error = open_error(db.path());
  EXPECT_NE(error.find(db.path()), std::string::npos) << error;
  EXPECT_NE(error.find("not an MBTiles file"), std::string::npos) << error;
}

TEST(Mbtiles, AnSqlDatabaseWithoutTilesIsNotMbtiles) {
  avk::testing::TempDb db("avk_mbtiles_other");
  {
    Connection c(db.path());
    c.exec("CREATE TABLE missions (id INTEGER PRIMARY KEY)");
  }
  const auto before = fs::file_size(db.path());
  const std::string error = open_error(db.path());
  EXPECT_NE(error.find(db.path()), std::string::npos) << error;
  EXPECT_NE(error.find("without a `tiles` table"), std::string::npos) << error;
  EXPECT_EQ(fs::file_size(db.path()), before);
}

}  // namespace
