// The per-frame work and canvas drawing of the debugging panels, which must happen whichever side
// tab is open: watches, validate(), frame times, autosave and lesson progress; the expression
// path and the violations over the canvas.
#include "ui/files/files.h"
#include "ui/files/settings.h"
#include "ui/panels/panels.h"

namespace dlab::ui {

void updateDebugPanels(AppState& state) {
    checkWatches(state);
    updateStatistics(state);
    saveAutosave(state);
    saveLessonProgressIfChanged(state);
}

void DrawDebugOverlays(AppState& state) {
    DrawViolationOverlay(state);
    DrawExpressionOverlay(state);
    DrawTraceCompareOverlay(state);
}

}  // namespace dlab::ui
