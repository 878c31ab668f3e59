#include "app/station_identity.hpp"

#include "app/store_access.hpp"
#include "store/postgresql.hpp"

#include <unistd.h>

#include <cctype>
#include <mutex>
#include <utility>

namespace avk::app {

namespace {

std::mutex g_mutex;

std::string& identity() {
  static std::string id = [] {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') return std::string("station");
    return std::string(host);
  }();
  return id;
}

}  // namespace

std::string station_id() {
  std::lock_guard lock(g_mutex);
  return identity();
}

void set_station_id(std::string id) {
  std::lock_guard lock(g_mutex);
  identity() = std::move(id);
}

std::optional<std::string> station_id_problem(const std::string& id) {
  if (id.empty()) return "must not be empty";
  if (id.size() > 64) return "must be at most 64 characters";
  for (const char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
      return "may hold only letters, digits, '.', '_' and '-'";
  return std::nullopt;
}

bool is_database_server(const std::string& db) {
  return store::is_postgresql_target(db);
}

std::unique_ptr<store::Store> open_station_store(const std::string& db) {
  auto s = std::make_unique<store::Store>(db);
  s->set_station_id(station_id());
  return s;
}

}  // namespace avk::app
