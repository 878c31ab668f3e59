#include "server/http/static_files.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <system_error>

#include "server/http/responses.hpp"

namespace avk::server {

namespace fs = std::filesystem;

namespace {

// The dashboard and nothing else that happens to lie in its folder (tests, package files,
// node_modules' bookkeeping): the page, its icon, css/ and js/, and the one library
// index.html loads.
bool is_dashboard_file(std::string_view relative) {
  return relative == "index.html" || relative == "favicon.svg" || relative.starts_with("css/") ||
         relative.starts_with("js/") || relative == "node_modules/plotly.js-dist-min/plotly.min.js";
}

}  // namespace

StaticFiles::StaticFiles(const std::optional<std::string>& root) {
  if (!root) return;
  std::error_code ec;
  fs::path canonical = fs::canonical(*root, ec);
  if (ec || !fs::is_directory(canonical, ec))
    throw std::runtime_error("web root is not a directory: " + *root);
  root_ = std::move(canonical);
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

std::optional<fs::path> StaticFiles::resolve(const std::string& decoded_path) const {
  if (!root_ || decoded_path.empty() || decoded_path.front() != '/') return std::nullopt;
  if (decoded_path.find('\0') != std::string::npos || decoded_path.find('\\') != std::string::npos)
    return std::nullopt;
  // Reject rather than normalise: a client that sends .. is not asking for anything we serve.
  std::string_view rest(decoded_path);
  while (!rest.empty()) {
    const auto slash = rest.find('/');
    if (rest.substr(0, slash) == "..") return std::nullopt;
    if (slash == std::string_view::npos) break;
    rest.remove_prefix(slash + 1);
  }
  std::string relative = decoded_path.substr(1);
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  if (!is_dashboard_file(relative)) return std::nullopt;

  std::error_code ec;
  const fs::path file = fs::canonical(*root_ / relative, ec);
  if (ec) return std::nullopt;
  // Symlinks are resolved by canonical(): what they point to must still be inside the root.
  const bool inside =
      std::mismatch(root_->begin(), root_->end(), file.begin(), file.end()).first == root_->end();
  if (!inside) return std::nullopt;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  return file;
}

http::message_generator StaticFiles::respond(const Request& req, const std::string& decoded_path,
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
  const auto file = resolve(decoded_path);
  if (!file) return not_found("no such file");

  beast::error_code ec;
  http::file_body::value_type body;
  body.open(file->c_str(), beast::file_mode::scan, ec);
  if (ec) return not_found("no such file");
  const auto size = body.size();

  if (head) {
    http::response<http::empty_body> res{http::status::ok, req.version()};
    set_common_headers(res);
    res.set(http::field::content_type, mime_type(*file));
    res.content_length(size);
    res.keep_alive(keep_alive);
    return res;
  }
  http::response<http::file_body> res{std::piecewise_construct, std::make_tuple(std::move(body)),
                                      std::make_tuple(http::status::ok, req.version())};
  set_common_headers(res);
  res.set(http::field::content_type, mime_type(*file));
  res.content_length(size);
  res.keep_alive(keep_alive);
  return res;
}

}  // namespace avk::server
