#include "kinematics/json_parse.hpp"

#include <string_view>
#include <utility>
#include <vector>

namespace avk::kinematics {

std::string json_error_reason(const nlohmann::json::exception& ex) {
  if (ex.id == 406) return "number is out of the range of a double";
  const std::string_view what = ex.what();
  if (what.find("UTF-8") != std::string_view::npos) return "string is not valid UTF-8";
  if (what.find("control character") != std::string_view::npos)
    return "string holds an unescaped control character";
  if (what.find("\\u") != std::string_view::npos || ex.id == 102 || ex.id == 103)
    return "string holds an invalid \\u escape";
  if (what.find("end of input") != std::string_view::npos) return "document ends early";
  return "syntax error";
}

namespace {

using nlohmann::json;

void append_pointer_token(std::string& out, std::string_view s) {
  for (char c : s) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
}

// Builds the DOM like nlohmann's own parser, but bounds depth, width and total size as it goes and
// rejects duplicate keys (which nlohmann would silently collapse to the last one).
class BoundedDomBuilder {
 public:
  BoundedDomBuilder(json& root, std::string_view text, const JsonLimits& limits)
      : root_(root), text_(text), limits_(limits) {}

  bool null() { return add(nullptr); }
  bool boolean(bool v) { return add(v); }
  bool number_integer(json::number_integer_t v) { return add(v); }
  bool number_unsigned(json::number_unsigned_t v) { return add(v); }
  bool number_float(json::number_float_t v, const json::string_t& /*text*/) { return add(v); }
  bool string(json::string_t& v) { return add(std::move(v)); }
  bool binary(json::binary_t& /*v*/) { fail("binary values are not JSON"); }

  bool start_object(std::size_t /*size*/) { return open(json::object()); }
  bool start_array(std::size_t /*size*/) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& k) {
    Frame& f = stack_.back();
    f.key = k;
    if (f.node->contains(k)) fail("duplicate key");
    if (f.node->size() >= limits_.max_object_keys)
      fail("object has more than " + std::to_string(limits_.max_object_keys) + " keys");
    return true;
  }

  [[noreturn]] bool parse_error(std::size_t position, const std::string& /*last_token*/,
                                const json::exception& ex) {
    // nlohmann counts bytes read including the offending one (and the end of input); step back
    // one to point at the byte itself.
    const std::size_t offset = position == 0 ? 0 : position - 1;
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < offset && i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw JsonSyntaxError(offset, pointer(), json_error_reason(ex), line, column);
  }

 private:
  struct Frame {
    json* node = nullptr;
    std::size_t next_index = 0;  // arrays: elements added so far
    std::string key;             // objects: key of the member being read
  };

  // Pointer to the value now being added, for errors raised while building.
  std::string pointer() const {
    std::string out;
    for (std::size_t d = 0; d < stack_.size(); ++d) {
      const Frame& f = stack_[d];
      out += '/';
      if (f.node->is_object()) {
        append_pointer_token(out, f.key);
      } else {
        const bool innermost = d + 1 == stack_.size();
        out += std::to_string(innermost ? f.next_index : f.next_index - 1);
      }
    }
    return out;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw ParseError(pointer(), 0, message);
  }

  template <class V>
  json* insert(V&& v) {
    if (++values_ > limits_.max_values)
      fail("document holds more than " + std::to_string(limits_.max_values) + " values");
    if (stack_.empty()) {
      root_ = json(std::forward<V>(v));
      return &root_;
    }
    Frame& f = stack_.back();
    if (f.node->is_array()) {
      if (f.next_index >= limits_.max_array_elements)
        fail("array holds more than " + std::to_string(limits_.max_array_elements) + " elements");
      f.node->push_back(json(std::forward<V>(v)));
      ++f.next_index;
      return &f.node->back();
    }
    json& slot = (*f.node)[f.key];
    slot = json(std::forward<V>(v));
    return &slot;
  }

  template <class V>
  bool add(V&& v) {
    insert(std::forward<V>(v));
    return true;
  }

  bool open(json container) {
    if (stack_.size() >= limits_.max_depth)
      fail("nested deeper than " + std::to_string(limits_.max_depth) + " levels");
    json* node = insert(std::move(container));
    stack_.push_back({node, 0, {}});
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  json& root_;
  std::string_view text_;
  const JsonLimits& limits_;
  std::vector<Frame> stack_;
  std::size_t values_ = 0;
};

}  // namespace

JsonSyntaxError::JsonSyntaxError(std::size_t offset, std::string pointer, std::string reason,
                                 std::size_t line, std::size_t column)
    : ParseError("json", offset,
                 "not valid JSON: " + reason + " at line " + std::to_string(line) + " column " +
                     std::to_string(column)),
      // The project names the whole document "/" (as its readers' "expected an object" do).
      pointer_(pointer.empty() ? "/" : std::move(pointer)),
      reason_(std::move(reason)),
      line_(line),
      column_(column),
      out_of_range_(reason_ == "number is out of the range of a double") {}

std::string json_member_pointer(std::string_view key) {
  std::string out = "/";
  append_pointer_token(out, key);
  return out;
}

json parse_json_bounded(std::string_view text, const JsonLimits& limits) {
  json root;
  BoundedDomBuilder builder(root, text, limits);
  // strict: anything but whitespace after the document is a syntax error.
  if (!json::sax_parse(text.begin(), text.end(), &builder, json::input_format_t::json, true)) {
    throw ParseError("json", 0, "JSON parser stopped without reporting an error");
  }
  return root;
}

}  // namespace avk::kinematics
