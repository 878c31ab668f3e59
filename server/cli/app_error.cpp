#include "server/cli/app_error.hpp"

#include <ostream>

namespace avk::server {

int report_error(const app::Error& e, Io& io, const std::string& command) {
  io.err << "avk " << command << ": ";
  if (e.code == app::ErrorCode::internal)
    io.err << "internal error (the database or the station): ";
  if (!e.field.empty()) io.err << e.field << ": ";
  io.err << e.message << "\n";
  for (const auto& f : e.fields)
    io.err << "  " << f.field << ": " << f.message << "\n";
  return e.code == app::ErrorCode::internal ? 3 : 1;
}

}  // namespace avk::server
