#pragma once
/// @file
/// One table of names per enum, the only place its spellings are written: the enum's to_string and
/// parser, the command-line choices (CLI11) and the scenario keys are all built from it.
///
///     inline constexpr EnumNames<Sweep, 2> sweep_names{{{Sweep::jacobi, "jacobi"}, {Sweep::gauss_seidel, "gauss-seidel"}}};
///     name_of(sweep_names, Sweep::jacobi)                 // "jacobi"
///     parse_name(sweep_names, "gauss-seidel", "--sweep")  // Sweep::gauss_seidel, or InputError
///     names_of(sweep_names)                               // {"jacobi", "gauss-seidel"}

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "laguerre/core/Error.hpp"

namespace laguerre::core {

/// One enum value and its name.
template <class E>
struct EnumName {
  E value;                ///< the value
  std::string_view name;  ///< its one spelling
};

/// The names of an enum's N values, in the order they are listed to users.
template <class E, std::size_t N>
using EnumNames = std::array<EnumName<E>, N>;

/// The name of `value`, or "?" if the table lacks it.
template <class E, std::size_t N>
constexpr std::string_view name_of(const EnumNames<E, N>& table, E value) {
  for (const auto& e : table)
    if (e.value == value) return e.name;
  return "?";
}

/// The value named `name`, or nothing.
template <class E, std::size_t N>
constexpr std::optional<E> find_name(const EnumNames<E, N>& table, std::string_view name) {
  for (const auto& e : table)
    if (e.name == name) return e.value;
  return std::nullopt;
}

/// Every name, in table order (for CLI::IsMember and the scenario loader's choices).
template <class E, std::size_t N>
std::vector<std::string> names_of(const EnumNames<E, N>& table) {
  std::vector<std::string> out;
  for (const auto& e : table) out.emplace_back(e.name);
  return out;
}

/// "a, b or c": the names as messages list them.
template <class E, std::size_t N>
std::string listed_names(const EnumNames<E, N>& table) {
  std::string s;
  for (std::size_t i = 0; i < N; ++i) s += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].name);
  return s;
}

/// The value named `name`. Throws InputError with `source` (an option, a key, or empty) as its source:
/// "found 'NAME', expected a, b or c".
template <class E, std::size_t N>
E parse_name(const EnumNames<E, N>& table, std::string_view name, const std::string& source = {}) {
  if (const auto v = find_name(table, name)) return *v;
  throw InputError(source, 0, "found '" + std::string(name) + "', expected " + listed_names(table));
}

}  // namespace laguerre::core
