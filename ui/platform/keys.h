// Key codes of ImGui's io.KeysDown[] in both platforms: GLFW's key codes (letters are their
// upper-case ASCII). The headless platform uses the same codes, so tests press the same keys.
#pragma once

namespace dlab::ui::key {

inline constexpr int kSpace = 32;
inline constexpr int kEscape = 256, kEnter = 257, kTab = 258, kBackspace = 259, kDelete = 261;
inline constexpr int kRight = 262, kLeft = 263, kDown = 264, kUp = 265;
inline constexpr int kPageUp = 266, kPageDown = 267, kHome = 268, kEnd = 269;
inline constexpr int kF1 = 290, kF12 = 301;
inline constexpr int kMinus = 45, kEqual = 61, kKpSubtract = 333, kKpAdd = 334;
inline constexpr int letter(char c) { return c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c; }

}  // namespace dlab::ui::key
