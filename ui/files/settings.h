// What the GUI remembers between runs: window placement, layout, overlays, presentation mode,
// animation speed and lesson progress, in $XDG_CONFIG_HOME/delaunay-lab/settings.json (JSON,
// written atomically under a lock; the progress as it changes, merged with other instances').
#pragma once

#include "ui/app_state.h"
#include "ui/platform/platform.h"

#include <cstddef>
#include <string>

namespace dlab::ui {

// $XDG_CONFIG_HOME/delaunay-lab/settings.json, else ~/.config/delaunay-lab/settings.json;
// empty when neither is known.
std::string defaultSettingsPath();

// The largest settings file read (they are a few hundred bytes).
inline constexpr std::size_t kMaxSettingsFileBytes = std::size_t{1} << 20;

// Reads what it can; a missing file is not an error. A damaged one (not JSON, not an object,
// binary) is renamed aside to PATH.bad-YYYYMMDD-HHMMSS, and `warning` says so (the defaults are
// used); one that cannot be read (a pipe, a device) is left alone with a warning. Never throws.
void loadSettings(const std::string& path, AppState& state, WindowOptions& window,
                  std::string& warning);
// Fits a remembered window into a monitor's work area (x, y, width, height: the screen less its
// panels): a size saved on a larger screen shrinks to the area, a position off it moves onto it.
void clampWindowToWorkArea(WindowOptions& window, int areaX, int areaY, int areaWidth,
                           int areaHeight);
// Writes everything, through the atomic writer (a temporary renamed over the old file), under an
// flock of PATH.lock: the lesson progress in the file (another instance's) is merged with
// `state`'s first (mergeProgress). False with a reason when it could not write, or when it wrote
// but found the file damaged (the reason then says where it was kept).
bool saveSettings(const std::string& path, const AppState& state, const WindowOptions& window,
                  std::string& error);
// Writes the lesson progress to state.lessonPlayer.settingsPath now, the same way: the file's
// other settings stay as they are, its lessons merge into `state`'s (which keeps the result).
bool saveLessonProgress(AppState& state, std::string& error);
// Called every frame: saveLessonProgress when the progress changed since the last write; a
// problem is logged in the messages once.
void saveLessonProgressIfChanged(AppState& state);
// The progress of one lesson kept by two writers: the furthest stop reached, every question
// answered in either (right over tried over not answered); `into`'s stop on show. A different
// title (another lesson at the same path) leaves `into` as it is.
void mergeProgress(LessonProgress& into, const LessonProgress& other);

}  // namespace dlab::ui
