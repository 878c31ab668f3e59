#pragma once
// The dashboard's files from a web root (only those: index.html, favicon.svg, css/, js/ and the
// Plotly bundle; never tests or package files): GET and HEAD only, no way out of the root (..
// segments, NUL, backslashes and symlinks that resolve elsewhere are all a plain 404), MIME types
// by extension so that browsers with nosniff still run the scripts.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "server/http/beast.hpp"

namespace avk::server {

class StaticFiles {
 public:
  // Throws std::runtime_error when the root is given but is not a directory.
  explicit StaticFiles(const std::optional<std::string>& root);

  // decoded_path: the request path, percent-decoded, without the query.
  http::message_generator respond(const Request& req, const std::string& decoded_path,
                                  bool keep_alive) const;

  static std::string_view mime_type(const std::filesystem::path& file);

 private:
  std::optional<std::filesystem::path> resolve(const std::string& decoded_path) const;

  std::optional<std::filesystem::path> root_;  // canonical
};

}  // namespace avk::server
