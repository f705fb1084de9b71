// What the GUI remembers between runs: window placement, layout, overlays, presentation mode
// and animation speed, in $XDG_CONFIG_HOME/delaunay-lab/settings.json (JSON, written atomically).
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

// Reads what it can; a missing file is not an error, a damaged one gives a warning (and the
// defaults). Never throws.
void loadSettings(const std::string& path, AppState& state, WindowOptions& window,
                  std::string& warning);
// Fits a remembered window into a monitor's work area (x, y, width, height: the screen less its
// panels): a size saved on a larger screen shrinks to the area, a position off it moves onto it.
void clampWindowToWorkArea(WindowOptions& window, int areaX, int areaY, int areaWidth,
                           int areaHeight);
// Writes to a temporary file and renames it over the old one. False with a reason on failure.
bool saveSettings(const std::string& path, const AppState& state, const WindowOptions& window,
                  std::string& error);

}  // namespace dlab::ui
