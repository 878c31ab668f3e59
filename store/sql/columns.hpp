#pragma once
// A table's columns named once: the list builds the statement text, and a row is read or bound by
// a name looked up in that same list at compile time. Adding a column is one name in the list and
// one line in the mapper; a name that is not in the list does not compile.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "store/database.hpp"

namespace avk::store::sql {

template <std::size_t N>
struct Columns {
  std::array<std::string_view, N> names;

  static constexpr int size() { return static_cast<int>(N); }

  // The 0-based result column of `name` in a SELECT of this list.
  consteval int operator[](std::string_view name) const {
    for (std::size_t i = 0; i < N; ++i)
      if (names[i] == name) return static_cast<int>(i);
    throw "no such column in the list";
  }
  // The 1-based parameter of `name` in an INSERT of this list.
  consteval int param(std::string_view name) const { return (*this)[name] + 1; }

  // "a, b, c", each name after `alias` ("c." in a query that joins).
  std::string list(std::string_view alias = {}) const {
    std::string out;
    for (const std::string_view name : names) {
      if (!out.empty()) out += ", ";
      out.append(alias).append(name);
    }
    return out;
  }
  // "a = excluded.a, b = excluded.b": an upsert's update of every column of this list.
  std::string set_from_excluded() const {
    std::string out;
    for (const std::string_view name : names) {
      if (!out.empty()) out += ", ";
      out.append(name).append(" = excluded.").append(name);
    }
    return out;
  }
  // "?, ?, ?": the VALUES of an INSERT of this list.
  static std::string placeholders() {
    std::string out;
    for (std::size_t i = 0; i < N; ++i)
      out += i == 0 ? "?" : ", ?";
    return out;
  }
};

template <typename... Names>
consteval Columns<sizeof...(Names)> columns(Names... names) {
  return {{std::string_view(names)...}};
}

// The columns of a, then those of b: a read of a table's row and more.
template <std::size_t A, std::size_t B>
consteval Columns<A + B> operator+(const Columns<A>& a, const Columns<B>& b) {
  Columns<A + B> out{};
  for (std::size_t i = 0; i < A; ++i)
    out.names[i] = a.names[i];
  for (std::size_t i = 0; i < B; ++i)
    out.names[A + i] = b.names[i];
  return out;
}

// A text column read back through `parse` (which returns an optional): a value this code does not
// know is a corrupt row, reported as "<row> has unknown <label> '<text>'", never taken for a
// default.
template <typename Parse>
auto parse_stored(const std::string& row, std::string_view label, const std::string& text,
                  Parse parse) {
  auto value = parse(text);
  if (!value) throw StoreError(row + " has unknown " + std::string(label) + " '" + text + "'");
  return *value;
}

// The id an INSERT ... RETURNING id gave back (both engines support RETURNING).
inline std::int64_t inserted_id(Statement& s) {
  if (!s.step()) throw StoreError("an insert returned no id");
  const std::int64_t id = s.column_int64(0);
  s.run();
  return id;
}

}  // namespace avk::store::sql
