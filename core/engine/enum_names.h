// One table of names per enum (locators, orders, boundaries, overlays, tabs): the CLI's choices
// and help, the GUI's combos, lessons and sessions all read the same table, so adding a value is
// one edit.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

template <class E>
struct EnumName {
    E value;
    std::string_view name;
};

// The name of `value`, "?" for a value the table lacks.
template <class E, std::size_t N>
constexpr std::string_view nameIn(const std::array<EnumName<E>, N>& table, E value) {
    for (const EnumName<E>& e : table)
        if (e.value == value) return e.name;
    return "?";
}

template <class E, std::size_t N>
constexpr std::optional<E> parseIn(const std::array<EnumName<E>, N>& table, std::string_view name) {
    for (const EnumName<E>& e : table)
        if (e.name == name) return e.value;
    return std::nullopt;
}

// Every name, in the table's order (the CLI's list of choices).
template <class E, std::size_t N>
std::vector<std::string> namesIn(const std::array<EnumName<E>, N>& table) {
    std::vector<std::string> out;
    for (const EnumName<E>& e : table) out.emplace_back(e.name);
    return out;
}

// Every value, in the table's order (a menu's entries).
template <class E, std::size_t N>
std::vector<E> valuesIn(const std::array<EnumName<E>, N>& table) {
    std::vector<E> out;
    for (const EnumName<E>& e : table) out.push_back(e.value);
    return out;
}

// "a | b | c": a help text's list.
template <class E, std::size_t N>
std::string joinedNames(const std::array<EnumName<E>, N>& table, std::string_view sep = " | ") {
    std::string out;
    for (const EnumName<E>& e : table) {
        if (!out.empty()) out += sep;
        out += e.name;
    }
    return out;
}

}  // namespace dlab
