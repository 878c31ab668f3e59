#include "server/cli/args.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace avk::server {

Args::Args(const std::vector<std::string>& words, const std::set<std::string>& value_options,
           const std::set<std::string>& flag_options,
           const std::set<std::string>& repeatable_options) {
  // Help wins over every other word, even one that is wrong: it is what a puzzled user types.
  if (std::any_of(words.begin(), words.end(),
                  [](const std::string& w) { return w == "--help" || w == "-h"; }))
    throw HelpRequested{};
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (w.rfind("--", 0) != 0 || w == "-") {
      positional_.push_back(w);
      continue;
    }
    std::string name = w.substr(2);
    std::optional<std::string> inline_value;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (flag_options.count(name)) {
      if (inline_value) throw UsageError("option --" + name + " takes no value");
      flags_.insert(name);
    } else if (value_options.count(name) || repeatable_options.count(name)) {
      if (values_.count(name) && !repeatable_options.count(name))
        throw UsageError("option --" + name + " given twice");
      if (inline_value) {
        values_[name].push_back(*inline_value);
      } else {
        if (i + 1 >= words.size()) throw UsageError("option --" + name + " needs a value");
        values_[name].push_back(words[++i]);
      }
    } else {
      throw UsageError("unknown option --" + name);
    }
  }
}

std::optional<std::string> Args::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second.back();
}

std::vector<std::string> Args::all(const std::string& name) const {
  const auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::string Args::require(const std::string& name) const {
  auto v = get(name);
  if (!v) throw UsageError("missing required option --" + name);
  return *v;
}

std::optional<double> Args::number(const std::string& name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  double d = 0.0;
  const auto r = std::from_chars(v->data(), v->data() + v->size(), d);
  if (r.ec != std::errc() || r.ptr != v->data() + v->size() || !std::isfinite(d)) {
    throw UsageError("option --" + name + " needs a finite number, got '" + *v + "'");
  }
  return d;
}

namespace {

std::vector<double> parse_number_list(const std::string& name, const std::string& text,
                                      std::size_t count, const std::string& shape) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find(',', pos);
    if (end == std::string::npos) end = text.size();
    double v = 0.0;
    const auto r = std::from_chars(text.data() + pos, text.data() + end, v);
    if (r.ec != std::errc() || r.ptr != text.data() + end || !std::isfinite(v)) break;
    out.push_back(v);
    pos = end + 1;
  }
  if (out.size() != count || pos <= text.size())
    throw UsageError("--" + name + " expects " + shape + ", got '" + text + "'");
  return out;
}

}  // namespace

std::optional<std::vector<double>> Args::number_list(const std::string& name, std::size_t count,
                                                     const std::string& shape) const {
  const auto text = get(name);
  if (!text) return std::nullopt;
  return parse_number_list(name, *text, count, shape);
}

std::vector<std::vector<double>> Args::number_lists(const std::string& name, std::size_t count,
                                                    const std::string& shape) const {
  std::vector<std::vector<double>> out;
  for (const std::string& text : all(name))
    out.push_back(parse_number_list(name, text, count, shape));
  return out;
}

}  // namespace avk::server
