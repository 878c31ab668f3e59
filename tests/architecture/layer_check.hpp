#pragma once
// The include-direction check: every quoted #include of a production file must point to a folder
// its layer may use (tests/architecture/layer_rules.txt). What CI runs over the tree, and what a
// test runs over a deliberately wrong tree to show that it fails.

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace avk::testing {

struct LayerRule {
  std::string folder;  // e.g. "server/http"
  // Folders or files, e.g. "kinematics", "server/api_types.hpp". "app!store": app, through its
  // headers that reach nothing of store, directly or through other app headers (a layer kept
  // from what is below the next).
  std::vector<std::string> allowed;
};

struct LayerViolation {
  std::string file;  // relative to the root, '/' separated
  int line = 0;
  std::string included;
  std::string folder;  // the rule the file fell under
  std::string hidden;  // what the included header reaches that the folder may not, if that
  std::string text() const;
};

// The regular files below root/folder for each folder (missing folders skipped) whose extension
// is one of `extensions` ("" for none), sorted and without repeats.
std::vector<std::filesystem::path> source_files(const std::filesystem::path& root,
                                                const std::vector<std::string>& folders,
                                                const std::vector<std::string>& extensions);

// Parses the rules; throws std::invalid_argument naming the line of a malformed one.
std::vector<LayerRule> parse_layer_rules(std::istream& in);

// Every .cpp/.hpp under the rules' folders below root, checked. Files outside every rule's folder
// (tests, benchmarks, tools) are not checked.
std::vector<LayerViolation> check_layers(const std::filesystem::path& root,
                                         const std::vector<LayerRule>& rules);

}  // namespace avk::testing
