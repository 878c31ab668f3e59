#include "app/db_copy.hpp"

#include "store/db_copy.hpp"
#include "store/postgresql.hpp"
#include "store/store.hpp"

namespace avk::app {

Result<std::vector<TableCopied>> copy_database(const std::string& from, const std::string& to) {
  if (from == to) return invalid_argument("to", "the source and the target are the same database");
  std::unique_ptr<store::Store> source, target;
  try {
    source = std::make_unique<store::Store>(from);
  } catch (const store::StoreError& e) {
    return internal_error("cannot open the source " + store::redacted_target(from) + ": " +
                          e.what());
  }
  try {
    target = std::make_unique<store::Store>(to);
  } catch (const store::StoreError& e) {
    return internal_error("cannot open the target " + store::redacted_target(to) + ": " + e.what());
  }
  try {
    std::vector<TableCopied> out;
    for (const auto& [table, rows] : store::copy_database(*source, *target))
      out.push_back({table, rows});
    return out;
  } catch (const store::StoreError& e) {
    const std::string what = e.what();
    if (what.find("copy into an empty database") != std::string::npos) return conflict(what);
    return internal_error(what);
  }
}

}  // namespace avk::app
