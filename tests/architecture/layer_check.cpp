#include "architecture/layer_check.hpp"

#include <algorithm>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace avk::testing {

namespace fs = std::filesystem;

namespace {

// "a/b" prefixes "a/b" and "a/b/c.hpp", not "a/bc.hpp".
bool under(const std::string& path, const std::string& prefix) {
  if (path == prefix) return true;
  return path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0 &&
         path[prefix.size()] == '/';
}

// A quoted include: the project's own headers.
const std::regex& include_pattern() {
  static const std::regex pattern("^\\s*#\\s*include\\s*\"([^\"]+)\"");
  return pattern;
}

const LayerRule* rule_of(const std::string& file, const std::vector<LayerRule>& rules) {
  const LayerRule* best = nullptr;
  for (const auto& r : rules)
    if (under(file, r.folder) && (!best || r.folder.size() > best->folder.size())) best = &r;
  return best;
}

// The first include under `hidden` that `header` (relative to root) reaches, directly or through
// the headers under `through` it includes; none when it reaches none. `seen` stops a cycle.
std::optional<std::string> hidden_include(const fs::path& root, const std::string& header,
                                          const std::string& through, const std::string& hidden,
                                          std::set<std::string>& seen) {
  if (!seen.insert(header).second) return std::nullopt;
  std::ifstream in(root / header);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, include_pattern())) continue;
    const std::string included = m[1];
    if (under(included, hidden)) return included;
    if (under(included, through))
      if (auto found = hidden_include(root, included, through, hidden, seen)) return found;
  }
  return std::nullopt;
}

}  // namespace

std::string LayerViolation::text() const {
  const std::string what = hidden.empty() ? "" : ", which includes \"" + hidden + "\"";
  return file + ":" + std::to_string(line) + ": includes \"" + included + "\"" + what + ", which " +
         folder + "/ may not use (tests/architecture/layer_rules.txt)";
}

std::vector<fs::path> source_files(const fs::path& root, const std::vector<std::string>& folders,
                                   const std::vector<std::string>& extensions) {
  std::vector<fs::path> files;
  for (const auto& folder : folders) {
    if (!fs::is_directory(root / folder)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / folder))
      if (e.is_regular_file() &&
          std::ranges::find(extensions, e.path().extension().string()) != extensions.end())
        files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

std::vector<LayerRule> parse_layer_rules(std::istream& in) {
  std::vector<LayerRule> rules;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto colon = line.find(':');
    std::istringstream folder_text(line.substr(0, colon));
    LayerRule r;
    folder_text >> r.folder;
    std::string extra;
    if (colon == std::string::npos || r.folder.empty() || (folder_text >> extra))
      throw std::invalid_argument("layer rules, line " + std::to_string(n) +
                                  ": expected 'folder: allowed...'");
    std::istringstream allowed(line.substr(colon + 1));
    for (std::string a; allowed >> a;)
      r.allowed.push_back(a);
    rules.push_back(std::move(r));
  }
  return rules;
}

std::vector<LayerViolation> check_layers(const fs::path& root,
                                         const std::vector<LayerRule>& rules) {
  std::vector<LayerViolation> out;
  std::vector<std::string> folders;
  for (const auto& r : rules)
    folders.push_back(r.folder);
  for (const auto& path : source_files(root, folders, {".cpp", ".hpp"})) {
    const std::string file = fs::relative(path, root).generic_string();
    const LayerRule* rule = rule_of(file, rules);
    if (!rule) continue;
    std::ifstream in(path);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      std::smatch m;
      if (!std::regex_search(line, m, include_pattern())) continue;
      const std::string included = m[1];
      // Only the project's own folders are layers; other quoted includes are the file's siblings.
      if (!rule_of(included, rules) && included.find('/') == std::string::npos) continue;
      // A file's own folder is the one whose rule it falls under: a sub-folder with a rule of
      // its own (server/http under server) is another layer, reached only when listed.
      const bool own = rule_of(included, rules) == rule;
      const std::string* entry = nullptr;
      for (const auto& a : rule->allowed)
        if (under(included, a.substr(0, a.find('!')))) entry = &a;
      if (!own && !entry) {
        out.push_back({file, n, included, rule->folder, {}});
      } else if (!own && entry->find('!') != std::string::npos) {
        const auto bang = entry->find('!');
        std::set<std::string> seen;
        if (auto inner = hidden_include(root, included, entry->substr(0, bang),
                                        entry->substr(bang + 1), seen))
          out.push_back({file, n, included, rule->folder, *inner});
      }
    }
  }
  return out;
}

}  // namespace avk::testing
