// The per-frame work and canvas drawing of issue 5's panels, which must happen whichever side
// tab is open: watches, validate(), frame times and autosave; the expression path and the
// violations over the canvas.
#include "ui/files/files.h"
#include "ui/panels/panels.h"

namespace dlab::ui {

void UpdateDebugPanels(AppState& state) {
    CheckWatches(state);
    UpdateStatistics(state);
    Autosave(state);
}

void DrawDebugOverlays(AppState& state) {
    DrawViolationOverlay(state);
    DrawExpressionOverlay(state);
    DrawTraceCompareOverlay(state);
}

}  // namespace dlab::ui
