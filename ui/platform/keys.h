// Key codes of ImGui's io.KeysDown[] in both platforms: GLFW's key codes (letters are their
// upper-case ASCII). The headless platform uses the same codes, so tests press the same keys.
// And the queue of key presses the application's shortcuts read: every press counts, even one
// whose release comes before the next frame (ImGui 1.86 only sees the keys down at a frame).
#pragma once

#include <utility>
#include <vector>

namespace dlab::ui {

// One press (or the system's auto-repeat of a held key), with the modifiers held at it.
struct KeyPress {
    int key = 0;
    bool shift = false, ctrl = false;
};

// The presses since the application last took them, oldest first: the window's key callback
// (platform_glfw.cpp, after ImGui's own) and the headless harness push them; handleShortcuts
// (app.cpp) takes them once a frame. One queue per process, as there is one window.
inline std::vector<KeyPress>& keyPressQueue() {
    static std::vector<KeyPress> queue;
    return queue;
}
inline void queueKeyPress(int key, bool shift, bool ctrl) {
    keyPressQueue().push_back({key, shift, ctrl});
}
inline std::vector<KeyPress> takeKeyPresses() { return std::exchange(keyPressQueue(), {}); }

}  // namespace dlab::ui

namespace dlab::ui::key {

inline constexpr int kSpace = 32;
inline constexpr int kEscape = 256, kEnter = 257, kTab = 258, kBackspace = 259, kDelete = 261;
inline constexpr int kRight = 262, kLeft = 263, kDown = 264, kUp = 265;
inline constexpr int kPageUp = 266, kPageDown = 267, kHome = 268, kEnd = 269;
inline constexpr int kF1 = 290, kF12 = 301;
inline constexpr int kMinus = 45, kEqual = 61, kKpSubtract = 333, kKpAdd = 334;
inline constexpr int letter(char c) { return c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c; }

}  // namespace dlab::ui::key
