#pragma once
// Reads one object of a JSON document, recording every problem (its JSON pointer and what is
// wrong) rather than stopping at the first one; fields it was not asked for are errors at
// finish(). Mission files and encounter scenario files are read with it.

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "kinematics/geometry.hpp"
#include "kinematics/text_limit.hpp"
#include "mission/mission_config.hpp"

namespace avk::mission {

class DocumentReader {
 public:
  DocumentReader(const nlohmann::json& obj, std::string path, std::vector<FieldError>& errors)
      : obj_(obj), path_(std::move(path)), errors_(errors) {
    ok_ = obj.is_object();
    if (!ok_) error(path_.empty() ? "/" : path_, "expected an object");
  }
  bool ok() const { return ok_; }

  void error(const std::string& field, const std::string& message) {
    errors_.push_back({field, message});
  }
  std::string at(const char* key) const { return path_ + "/" + key; }

  const nlohmann::json* get(const char* key, bool required) {
    known_.insert(key);
    if (!ok_) return nullptr;
    const auto it = obj_.find(key);
    if (it == obj_.end()) {
      if (required) error(at(key), "missing required field");
      return nullptr;
    }
    return &*it;
  }

  void number(const char* key, double& target, double min, double max, bool required = false,
              bool min_exclusive = false) {
    const nlohmann::json* v = get(key, required);
    if (!v) return;
    if (!v->is_number() || !std::isfinite(v->get<double>())) {
      error(at(key), "expected a number");
      return;
    }
    const double d = v->get<double>();
    if (d < min || d > max || (min_exclusive && d == min)) {
      error(at(key), std::string("must be ") + (min_exclusive ? "> " : ">= ") +
                         nlohmann::json(min).dump() + " and <= " + nlohmann::json(max).dump() +
                         ", got " + v->dump());
      return;
    }
    target = d;
  }

  void integer(const char* key, int& target, int min, int max) {
    const nlohmann::json* v = get(key, false);
    if (!v) return;
    if (!v->is_number_integer() || v->get<long long>() < min || v->get<long long>() > max) {
      error(at(key),
            "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max));
      return;
    }
    target = static_cast<int>(v->get<long long>());
  }

  // Free text is always bounded (kinematics/text_limit.hpp); it must not be empty when required.
  void text(const char* key, std::string& target, bool required, std::size_t max_bytes) {
    const nlohmann::json* v = get(key, required);
    if (!v) return;
    if (!v->is_string() || (required && v->get_ref<const std::string&>().empty())) {
      error(at(key), required ? "expected a non-empty string" : "expected a string");
      return;
    }
    if (const auto why = kinematics::text_too_long(v->get_ref<const std::string&>(), max_bytes)) {
      error(at(key), *why);
      return;
    }
    target = v->get<std::string>();
  }

  std::optional<kinematics::Point> point(const nlohmann::json& v, const std::string& field) {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() ||
        !std::isfinite(v[0].get<double>()) || !std::isfinite(v[1].get<double>())) {
      error(field, "expected [x_m, y_m]");
      return std::nullopt;
    }
    return kinematics::Point{v[0].get<double>(), v[1].get<double>()};
  }

  void finish() {
    if (!ok_) return;
    for (const auto& [k, v] : obj_.items()) {
      if (!known_.count(k)) error(path_ + "/" + k, "unknown field");
    }
  }

 private:
  const nlohmann::json& obj_;
  std::string path_;
  std::vector<FieldError>& errors_;
  std::set<std::string> known_;
  bool ok_ = true;
};

}  // namespace avk::mission
