// Files: point sets (open .node/.csv/.xy/.pts, save .node/.csv), any file dropped on the window
// (points or a session), mesh exports (.ele/.neigh, OFF, OBJ), an SVG of the current view, PNG
// screenshots (F12) and animated GIFs of a range of steps, autosave of the user's points and the
// offer to recover them after a crash. Every failure is one line naming the file (and line): it
// goes to the message log and to a notice over the canvas, and changes nothing.
#pragma once

#include "ui/app_state.h"

#include <iosfwd>
#include <string>

namespace dlab::ui {

class Gui;

// Reports a file error: the message log and the notice over the canvas.
void fileError(AppState& state, const std::string& line);

// A point file or a session (.json, or any file whose first character is '{'). False after a
// fileError when it cannot be read; the state is then unchanged.
bool openFile(AppState& state, const std::string& path);
// The points as Triangle .node or CSV (by the extension: .node, else .csv / .xy / .txt).
bool savePoints(AppState& state, const std::string& path);
bool saveSessionFile(AppState& state, const std::string& path);

enum class MeshFormat : std::uint8_t { Triangle, Off, Obj };
// The mesh on the screen without its virtual (ghost / super) triangles: what exports write.
// Vertex ids are input indices; G holds every input point (duplicates too, unused).
Mesh exportableMesh(const Engine& engine);
// Triangle: BASE.node, BASE.ele, BASE.neigh beside `path` (whatever its extension); OFF and OBJ:
// `path` itself.
bool exportMesh(AppState& state, const std::string& path, MeshFormat format);
// The canvas as it is now (view, mesh, the current operation's highlights, points, caption).
void writeViewSvg(std::ostream& os, const AppState& state);
bool exportViewSvg(AppState& state, const std::string& path);

// Work that needs the renderer, requested by keys and dialogs (F12, the GIF dialog): the main
// loop and tests call it after each frame.
void serviceCaptures(Gui& gui);
// A PNG of the whole window; an empty path picks delaunay-lab-YYYYMMDD-HHMMSS.png in
// state.files.screenshotFolder.
bool saveScreenshotFile(Gui& gui, std::string path = {});

// ---- Autosave and recovery --------------------------------------------------------------------
// The folder: $XDG_CACHE_HOME/delaunay-lab, else ~/.cache/delaunay-lab; empty when unknown.
std::string defaultAutosaveFolder();
// Each running instance writes FOLDER/autosave-PID.json (a session) after every change of its
// points, atomically. The points now are taken as saved already.
void enableAutosave(AppState& state, const std::string& folder);
// Called every frame: writes the autosave when the points changed since the last one.
void saveAutosave(AppState& state);
// Looks for an autosave left by an instance that is not running any more (a crash, kill -9);
// the newest is offered (state.files.recoveryPath) by a dialog. True when there is one.
bool offerRecovery(AppState& state, const std::string& folder);
// The dialog's answers: restore the session (then the old file goes), or delete it.
bool acceptRecovery(AppState& state);
void declineRecovery(AppState& state);
// A clean exit: this instance's autosave is removed (a pending offer stays on disk).
void removeAutosave(AppState& state);

}  // namespace dlab::ui
