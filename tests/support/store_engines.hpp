#pragma once
// Store tests run on both engines: a test written once with TEST_P over a fixture derived from
// OnEachEngine, and AVK_ON_EACH_ENGINE(Fixture) instantiates it for SQLite (a temporary file) and
// PostgreSQL (a fresh database of the test cluster, support/pg_cluster.hpp).

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

#include "store/database.hpp"
#include "support/pg_cluster.hpp"
#include "support/temp_db.hpp"

namespace avk::testing {

// A fresh, empty database of one engine, removed afterwards.
class EngineDb {
 public:
  explicit EngineDb(store::Engine engine) {
    if (engine == store::Engine::sqlite)
      file_ = std::make_unique<TempDb>();
    else
      pg_ = std::make_unique<PgTestDb>();
  }
  // What Store(...) and `--db` take.
  std::string target() const { return file_ ? file_->path() : pg_->conninfo(); }

 private:
  std::unique_ptr<TempDb> file_;
  std::unique_ptr<PgTestDb> pg_;
};

class OnEachEngine : public ::testing::TestWithParam<store::Engine> {
 protected:
  store::Engine engine() const { return GetParam(); }
  // This test's database, made on first use.
  const std::string& db() {
    if (!target_) {
      dbs_.push_back(std::make_unique<EngineDb>(engine()));
      target_ = dbs_.back()->target();
    }
    return *target_;
  }
  // Another fresh database of the same engine.
  std::string another_db() {
    dbs_.push_back(std::make_unique<EngineDb>(engine()));
    return dbs_.back()->target();
  }

 private:
  std::optional<std::string> target_;
  std::vector<std::unique_ptr<EngineDb>> dbs_;
};

inline std::string engine_test_name(const ::testing::TestParamInfo<store::Engine>& info) {
  return store::to_string(info.param);
}

}  // namespace avk::testing

#define AVK_ON_EACH_ENGINE(Fixture)                                                      \
  INSTANTIATE_TEST_SUITE_P(                                                              \
      Engines, Fixture,                                                                  \
      ::testing::Values(::avk::store::Engine::sqlite, ::avk::store::Engine::postgresql), \
      ::avk::testing::engine_test_name)
