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

// One line for a message: control characters written as escapes ("\\n", "\\t", "\\x01"), so
// that user text quoted in an error can never split it.
inline std::string escapeControls(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char ch : s) {
        const auto u = static_cast<unsigned char>(ch);
        if (ch == '\n')
            out += "\\n";
        else if (ch == '\r')
            out += "\\r";
        else if (ch == '\t')
            out += "\\t";
        else if (u < 0x20 || u == 0x7f) {
            static const char* const kHex = "0123456789abcdef";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else {
            out += ch;
        }
    }
    return out;
}

// Untrusted text for a terminal, over several lines: newlines and tabs kept, every other
// control character (ESC, BEL, a lone CR...) written as an escape, as escapeControls does.
inline std::string escapeControlsKeepLines(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    std::size_t from = 0;
    for (std::size_t i = 0; i <= s.size(); ++i) {
        if (i == s.size() || s[i] == '\n' || s[i] == '\t') {
            out += escapeControls(s.substr(from, i - from));
            if (i < s.size()) out += s[i];
            from = i + 1;
        }
    }
    return out;
}

}  // namespace dlab
