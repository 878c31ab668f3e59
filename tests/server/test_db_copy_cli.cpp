// `avk db copy` of a results database SQLite -> PostgreSQL -> SQLite: the comparison of the
// prediction methods and the exported CKT file read the same from all three (the file differs
// only in the moment it was written, its created_utc), and a copy into a database that holds
// data is refused with the reason.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "support/cli_run.hpp"
#include "support/pg_cluster.hpp"
#include "support/temp_db.hpp"
#include "support/temp_dir.hpp"

namespace {

using avk::testing::example;
using avk::testing::run;

std::string exported_ckt(const std::string& db, const std::string& file) {
  const auto r = run({"ckt", "export", "--db", db, "--out", file});
  EXPECT_EQ(r.rc, 0) << r.err;
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return std::regex_replace(ss.str(), std::regex(R"("created_utc": "[^"]*")"),
                            "\"created_utc\": \"(when written)\"");
}

TEST(DbCopyCli, SqliteToPostgresqlToSqliteGivesTheSameComparisonAndTable) {
  avk::testing::TempDb first("avk_copy_first"), last("avk_copy_last");
  avk::testing::PgTestDb pg;
  avk::testing::TempDir dir("avk_copy_cli");
  for (const char* seed : {"1", "2"})
    ASSERT_EQ(
        run({"mission", "run", "--config", example("thesis-fig4-1.json"), "--db", first.path(),
             "--sim", "--sim-config", example("sim-choppy.json"), "--seed", seed, "--quiet"})
            .rc,
        0);
  ASSERT_EQ(run({"model", "fit", "--db", first.path(), "--mission", "1", "--form", "thesis"}).rc,
            0);

  const auto there = run({"db", "copy", "--from", first.path(), "--to", pg.url()});
  ASSERT_EQ(there.rc, 0) << there.err;
  EXPECT_NE(there.out.find("every table's count matches"), std::string::npos) << there.out;
  const auto back = run({"db", "copy", "--from", pg.conninfo(), "--to", last.path()});
  ASSERT_EQ(back.rc, 0) << back.err;

  const auto compare = [](const std::string& db) {
    const auto r = run({"compare", "--db", db, "--model", "1", "--format", "json", "--mission", "1",
                        "--test-mission", "2"});
    EXPECT_EQ(r.rc, 0) << r.err;
    return r.out;
  };
  const std::string original = compare(first.path());
  ASSERT_GT(original.size(), 100u);
  EXPECT_EQ(compare(pg.url()), original);
  EXPECT_EQ(compare(last.path()), original);
  const std::string table = exported_ckt(first.path(), (dir.path() / "first.json").string());
  EXPECT_EQ(exported_ckt(pg.url(), (dir.path() / "pg.json").string()), table);
  EXPECT_EQ(exported_ckt(last.path(), (dir.path() / "last.json").string()), table);

  // The PostgreSQL database now holds data: a second copy into it is refused, naming why.
  const auto again = run({"db", "copy", "--from", first.path(), "--to", pg.url()});
  EXPECT_EQ(again.rc, 1);
  EXPECT_NE(again.err.find("empty database"), std::string::npos) << again.err;
}

}  // namespace
