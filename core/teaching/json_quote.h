// A JSON value quoted in an error message, bounded whatever the value: small values as written,
// deep or large ones by their kind and size (dump() recurses once per level of nesting).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace dlab {

// Whether `v` has at most `maxValues` values in all, nested at most `maxDepth` deep (counted
// with a stack of its own: no recursion).
template <class Json>
bool jsonIsSmall(const Json& v, std::size_t maxValues = 32, std::size_t maxDepth = 8) {
    std::vector<std::pair<const Json*, std::size_t>> stack = {{&v, 0}};
    std::size_t seen = 0;
    while (!stack.empty()) {
        const auto [j, depth] = stack.back();
        stack.pop_back();
        if (++seen > maxValues || depth > maxDepth) return false;
        if (j->is_array() || j->is_object()) {
            if (j->size() > maxValues) return false;
            for (const auto& child : *j) stack.push_back({&child, depth + 1});
        }
    }
    return true;
}

// The value as JSON text when it is small (cut at 60 characters), else "an array of N values" or
// "an object of N fields"; always one line (dump() escapes control characters).
template <class Json>
std::string quoteJson(const Json& v) {
    if (!jsonIsSmall(v)) {
        return v.is_array() ? "an array of " + std::to_string(v.size()) + " values"
                            : "an object of " + std::to_string(v.size()) + " fields";
    }
    std::string s = v.dump();
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

}  // namespace dlab
