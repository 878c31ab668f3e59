#pragma once
// The dashboard's files from a web root (only those: index.html, favicon.svg, css/, js/ and the
// Plotly bundle; never tests or package files): GET and HEAD only, no way out of the root (..
// segments, NUL, backslashes and symlinks that resolve elsewhere are all a plain 404), MIME types
// by extension so that browsers with nosniff still run the scripts.
//
// The files are found, resolved and checked once, when the server starts: a request is a lookup
// in that list, never a walk of the file system. Each file's bytes are kept in memory and read
// again when its size or modification time changes (one lstat per request), so an edited file
// is served as it is now; a file added later is not served until a restart. Answers carry an
// ETag and Last-Modified, Cache-Control: no-cache (a browser asks again, and gets a 304 while the
// file is unchanged), and If-None-Match / If-Modified-Since are answered with 304.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "server/http/beast.hpp"
#include "server/http/response_generator.hpp"

namespace avk::server {

class StaticFiles {
 public:
  // Throws std::runtime_error when the root is given but is not a directory.
  explicit StaticFiles(const std::optional<std::string>& root);

  // decoded_path: the request path, percent-decoded, without the query.
  ResponseGenerator respond(const Request& req, const std::string& decoded_path,
                            bool keep_alive) const;

  static std::string_view mime_type(const std::filesystem::path& file);

  // RFC 9110's IMF-fixdate ("Sun, 06 Nov 1994 08:49:37 GMT") of seconds since 1970, and back;
  // none for text in another form.
  static std::string http_date(std::int64_t unix_s);
  static std::optional<std::int64_t> parse_http_date(std::string_view text);

 private:
  // One file as last read: its bytes and what the validators are made of.
  struct Snapshot {
    std::uint64_t size = 0;
    std::int64_t mtime_ns = 0;
    std::shared_ptr<const std::string> bytes;
    std::string etag;
    std::string last_modified;
    std::int64_t mtime_s = 0;
  };
  struct File {
    std::filesystem::path path;  // canonical, inside the root
    std::string_view mime;
    mutable std::mutex mutex;
    mutable std::shared_ptr<const Snapshot> current;
  };
  // The file's bytes as they are now; null when it is gone or no longer a regular file.
  std::shared_ptr<const Snapshot> snapshot(const File& file) const;
  const File* find(const std::string& decoded_path) const;

  std::optional<std::filesystem::path> root_;                        // canonical
  std::map<std::string, std::unique_ptr<File>, std::less<>> files_;  // by path below the root
};

}  // namespace avk::server
