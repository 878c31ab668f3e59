#include "server/http/static_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "server/http/responses.hpp"
#include "server/http/shared_text_body.hpp"

namespace avk::server {

namespace fs = std::filesystem;

namespace {

// The dashboard and nothing else that happens to lie in its folder (tests, package files,
// node_modules' bookkeeping): the page, its icon, everything under css/ and js/, and the one
// library index.html loads.
constexpr std::array<std::string_view, 3> kDashboardFiles = {
    "index.html", "favicon.svg", "node_modules/plotly.js-dist-min/plotly.min.js"};
constexpr std::array<std::string_view, 2> kDashboardFolders = {"css", "js"};

constexpr std::array<std::string_view, 7> kDays = {"Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat"};
constexpr std::array<std::string_view, 12> kMonths = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                                      "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};

bool inside(const fs::path& root, const fs::path& file) {
  return std::mismatch(root.begin(), root.end(), file.begin(), file.end()).first == root.end();
}

// RFC 9110 8.8.3.2: If-None-Match compares weakly, so W/"x" matches "x"; "*" matches any file.
bool etag_listed(std::string_view header, std::string_view etag) {
  while (!header.empty()) {
    const auto comma = std::min(header.find(','), header.size());
    std::string_view item = header.substr(0, comma);
    header.remove_prefix(std::min(comma + 1, header.size()));
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t'))
      item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t'))
      item.remove_suffix(1);
    if (item == "*") return true;
    if (item.starts_with("W/")) item.remove_prefix(2);
    if (item == etag) return true;
  }
  return false;
}

std::optional<int> number(std::string_view text) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

}  // namespace

StaticFiles::StaticFiles(const std::optional<std::string>& root) {
  if (!root) return;
  std::error_code ec;
  fs::path canonical = fs::canonical(*root, ec);
  if (ec || !fs::is_directory(canonical, ec))
    throw std::runtime_error("web root is not a directory: " + *root);
  root_ = std::move(canonical);
  // Resolved once: symlinks are followed here, and what they point to must lie inside the root.
  const auto add = [&](const std::string& relative) {
    std::error_code file_ec;
    const fs::path file = fs::canonical(*root_ / relative, file_ec);
    if (file_ec || !inside(*root_, file) || !fs::is_regular_file(file, file_ec)) return;
    auto entry = std::make_unique<File>();
    entry->path = file;
    entry->mime = mime_type(file);
    files_.emplace(relative, std::move(entry));
  };
  for (const auto name : kDashboardFiles)
    add(std::string(name));
  for (const auto folder : kDashboardFolders) {
    std::error_code walk_ec;
    for (fs::recursive_directory_iterator it(*root_ / folder, walk_ec), end; !walk_ec && it != end;
         it.increment(walk_ec))
      add(fs::relative(it->path(), *root_, walk_ec).generic_string());
  }
}

std::string_view StaticFiles::mime_type(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".html" || ext == ".htm") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".webp") return "image/webp";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".woff2") return "font/woff2";
  if (ext == ".txt") return "text/plain; charset=utf-8";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

std::string StaticFiles::http_date(std::int64_t unix_s) {
  using namespace std::chrono;
  const sys_seconds t{seconds(unix_s)};
  const auto day = floor<days>(t);
  const year_month_day ymd{day};
  const hh_mm_ss hms{t - day};
  char out[40];
  std::snprintf(out, sizeof out, "%s, %02u %s %04d %02d:%02d:%02d GMT",
                kDays[weekday(day).c_encoding()].data(), static_cast<unsigned>(ymd.day()),
                kMonths[static_cast<unsigned>(ymd.month()) - 1].data(),
                static_cast<int>(ymd.year()), static_cast<int>(hms.hours().count()),
                static_cast<int>(hms.minutes().count()), static_cast<int>(hms.seconds().count()));
  return out;
}

std::optional<std::int64_t> StaticFiles::parse_http_date(std::string_view text) {
  // "Sun, 06 Nov 1994 08:49:37 GMT": fixed width. The obsolete forms RFC 9110 still lets a
  // recipient accept are not worth it here: an unreadable date only costs a full answer.
  if (text.size() != 29 || text.substr(3, 2) != ", " || text[7] != ' ' || text[11] != ' ' ||
      text[16] != ' ' || text[19] != ':' || text[22] != ':' || text.substr(25) != " GMT")
    return std::nullopt;
  const auto month = std::find(kMonths.begin(), kMonths.end(), text.substr(8, 3));
  const auto d = number(text.substr(5, 2));
  const auto y = number(text.substr(12, 4));
  const auto h = number(text.substr(17, 2));
  const auto mi = number(text.substr(20, 2));
  const auto s = number(text.substr(23, 2));
  if (month == kMonths.end() || !d || !y || !h || !mi || !s || *h > 23 || *mi > 59 || *s > 60)
    return std::nullopt;
  using namespace std::chrono;
  const year_month_day ymd{year(*y),
                           std::chrono::month(static_cast<unsigned>(month - kMonths.begin()) + 1),
                           day(static_cast<unsigned>(*d))};
  if (!ymd.ok()) return std::nullopt;
  const auto t = sys_days(ymd) + hours(*h) + minutes(*mi) + seconds(*s);
  return duration_cast<seconds>(t.time_since_epoch()).count();
}

const StaticFiles::File* StaticFiles::find(const std::string& decoded_path) const {
  if (!root_ || decoded_path.empty() || decoded_path.front() != '/') return nullptr;
  std::string relative = decoded_path.substr(1);
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  const auto it = files_.find(relative);
  return it == files_.end() ? nullptr : it->second.get();
}

std::shared_ptr<const StaticFiles::Snapshot> StaticFiles::snapshot(const File& file) const {
  // lstat: a file replaced by a symlink since the start is not followed.
  struct stat st {};
  if (::lstat(file.path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return nullptr;
  const auto mtime_ns = [](const struct stat& s) {
    return static_cast<std::int64_t>(s.st_mtim.tv_sec) * 1'000'000'000 + s.st_mtim.tv_nsec;
  };
  std::lock_guard lock(file.mutex);
  if (file.current && file.current->size == static_cast<std::uint64_t>(st.st_size) &&
      file.current->mtime_ns == mtime_ns(st))
    return file.current;
  const int fd = ::open(file.path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return nullptr;
  std::string bytes;
  bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  if (ok) {
    bytes.resize(static_cast<std::size_t>(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
      const auto n = ::read(fd, bytes.data() + got, bytes.size() - got);
      if (n <= 0) break;
      got += static_cast<std::size_t>(n);
    }
    // A file cut short while read is served as it was read; its validators then change with it.
    bytes.resize(got);
  }
  ::close(fd);
  if (!ok) return nullptr;
  Snapshot s;
  s.size = static_cast<std::uint64_t>(st.st_size);
  s.mtime_ns = mtime_ns(st);
  s.mtime_s = static_cast<std::int64_t>(st.st_mtim.tv_sec);
  char etag[48];
  std::snprintf(etag, sizeof etag, "\"%llx-%llx\"", static_cast<unsigned long long>(s.size),
                static_cast<unsigned long long>(s.mtime_ns));
  s.etag = etag;
  s.last_modified = http_date(s.mtime_s);
  s.bytes = std::make_shared<const std::string>(std::move(bytes));
  file.current = std::make_shared<const Snapshot>(std::move(s));
  return file.current;
}

ResponseGenerator StaticFiles::respond(const Request& req, const std::string& decoded_path,
                                       bool keep_alive) const {
  const bool head = req.method() == http::verb::head;
  const auto not_found = [&](std::string_view detail) {
    return body_unless_head(
        head, problem_response(http::status::not_found, detail, req.version(), keep_alive));
  };
  if (!root_) return not_found("no such resource");
  if (req.method() != http::verb::get && !head) {
    auto res =
        problem_response(http::status::method_not_allowed, "static files are read with GET or HEAD",
                         req.version(), keep_alive);
    res.set(http::field::allow, "GET, HEAD");
    return res;
  }
  const File* file = find(decoded_path);
  if (!file) return not_found("no such file");
  const auto s = snapshot(*file);
  if (!s) return not_found("no such file");

  const auto headers = [&](auto& res) {
    set_common_headers(res);
    res.set(http::field::etag, s->etag);
    res.set(http::field::last_modified, s->last_modified);
    // Stored, but asked about again before each use: an updated dashboard is never run from a
    // stale copy, and an unchanged one costs a 304.
    res.set(http::field::cache_control, "no-cache");
    res.keep_alive(keep_alive);
  };
  // RFC 9110 13.1.3: If-Modified-Since counts only without If-None-Match.
  const auto if_none_match = req[http::field::if_none_match];
  const auto since =
      if_none_match.empty() ? parse_http_date(req[http::field::if_modified_since]) : std::nullopt;
  if (if_none_match.empty() ? since && s->mtime_s <= *since : etag_listed(if_none_match, s->etag)) {
    http::response<http::empty_body> res{http::status::not_modified, req.version()};
    headers(res);
    return res;
  }
  if (head) {
    http::response<http::empty_body> res{http::status::ok, req.version()};
    headers(res);
    res.set(http::field::content_type, file->mime);
    res.content_length(s->bytes->size());
    return res;
  }
  http::response<SharedTextBody> res{http::status::ok, req.version()};
  headers(res);
  res.set(http::field::content_type, file->mime);
  res.body() = s->bytes;
  res.prepare_payload();
  return res;
}

}  // namespace avk::server
