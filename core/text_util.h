// Small text helpers shared by the readers of lessons, breakpoints and traces: trimming, case
// folding, and the loose comparison of names that people type ("split edge" = "SplitEdge").
#pragma once

#include <cctype>
#include <string>
#include <string_view>

namespace dlab {

inline std::string trimmed(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return std::string(s);
}

inline std::string lowered(std::string s) {
    for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

// Lower case, without spaces, tabs, '-' and '_'.
inline std::string looseName(std::string_view s) {
    std::string out;
    for (char ch : s) {
        if (ch == ' ' || ch == '\t' || ch == '-' || ch == '_') continue;
        out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    }
    return out;
}

}  // namespace dlab
