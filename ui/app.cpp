// The application's layout (Debian's ImGui 1.86 has no docking): one host window filling the
// display, with a menu bar, the toolbar and caption, the canvas in the middle, the tables and
// inspector in a side column, messages below; splitters between them, remembered in Layout.
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <imgui.h>

#include <algorithm>

namespace dlab::ui {

namespace {

// Short labels, so that every tab shows whole in a 1600-pixel window; the full title in the
// tooltip (and as the name tests and lessons find it by).
const SideTab kSideTabs[] = {
    {"Corners", ShowCornerTable, "corner-table", "Corner table"},
    {"G", ShowVertexTable, "vertex-table", "G (vertices)"},
    {"Expressions", ShowExpressions, "expressions", "Expressions"},
    {"Predicates", ShowPredicates, "predicates", "Predicates"},
    {"ID buffer", ShowIdBuffer, "idbuffer", "ID buffer"},
    {"Statistics", ShowStatistics, "statistics", "Statistics"},
    {"Trace", ShowTraceCompare, "trace-compare", "Student trace"},
};

// A draggable bar; returns the drag delta in pixels along its axis.
float Splitter(const char* id, bool vertical, float thickness, float length) {
    ImGui::InvisibleButton(id, vertical ? ImVec2(thickness, length) : ImVec2(length, thickness));
    const bool active = ImGui::IsItemActive();
    if (ImGui::IsItemHovered() || active) {
        ImGui::SetMouseCursor(vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
        const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
        ImGui::GetWindowDrawList()->AddRectFilled(
            a, b,
            ImGui::GetColorU32(active ? ImGuiCol_SeparatorActive : ImGuiCol_SeparatorHovered));
    }
    if (!active) return 0.0f;
    return vertical ? ImGui::GetIO().MouseDelta.x : ImGui::GetIO().MouseDelta.y;
}

constexpr float kBar = 6.0f;  // the splitters' thickness

// What happens before the frame is drawn: shortcuts, the run's animation, the debug panels'
// checks, and a notice from the engine (which stops the run, and shows over the canvas).
void UpdateBeforeDrawing(AppState& state) {
    handleShortcuts(state);
    advanceRun(state, ImGui::GetIO().DeltaTime);
    updateDebugPanels(state);  // watches (may pause the run), checks, autosave
    if (std::string notice = state.engine.takeNotice(); !notice.empty()) {
        state.run.running = false;
        state.log(Message::Level::Warning, notice);
        state.files.notice = notice;
    }
}

// The host window filling the display, with a menu bar; the caller ends it.
void BeginHostWindow() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos);
    ImGui::SetNextWindowSize(vp->WorkSize);
    const ImGuiWindowFlags hostFlags =
        ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
        ImGuiWindowFlags_MenuBar | ImGuiWindowFlags_NoBringToFrontOnFocus |
        ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoBackground;  // the frame's clear
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 4));
    ImGui::Begin("Delaunay Lab", nullptr, hostFlags);
    ImGui::PopStyleVar();
}

// The sizes of the three regions, from the space below the toolbar and the Layout fractions.
struct Regions {
    ImVec2 avail;
    float mainH = 0, sideW = 0, canvasW = 0;
};

Regions MeasureRegions(const AppState& state) {
    const Layout& L = state.layout;
    Regions r;
    r.avail = ImGui::GetContentRegionAvail();
    const float bottomH = std::clamp(L.bottomHeight * r.avail.y, 40.0f, r.avail.y * 0.6f);
    r.mainH = std::max(100.0f, r.avail.y - bottomH - kBar);
    r.sideW = state.presentation ? std::clamp(L.rightWidth * r.avail.x, 0.0f, r.avail.x * 0.7f)
                                 : std::clamp(L.rightWidth * r.avail.x, 220.0f, r.avail.x * 0.7f);
    r.canvasW = std::max(100.0f, r.avail.x - r.sideW - kBar);
    return r;
}

// Left: the canvas with its overlays, and the timeline.
void ShowLeftColumn(AppState& state, const Regions& r) {
    ImGui::BeginChild("##left", ImVec2(r.canvasW, r.mainH), false,
                      ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
    ShowCanvas(state);
    DrawDebugOverlays(state);
    ShowCanvasLegend(state);
    ShowCanvasNotice(state);
    ShowTimeline(state);
    ImGui::EndChild();
}

// The lesson pane at the top of the side column, when a lesson is open, and the splitter below
// it; returns the height left for the rest of the column.
float ShowLessonPane(AppState& state, const Regions& r) {
    if (!state.lessonPlayer.lesson) return r.mainH;
    Layout& L = state.layout;
    const float lessonH = std::clamp(L.lessonHeight * r.mainH, 120.0f, r.mainH - 60.0f);
    ImGui::BeginChild("##lesson", ImVec2(0, lessonH), true);
    ShowLesson(state);
    ImGui::EndChild();
    if (const float d = Splitter("##lsplit", false, kBar, r.sideW); d != 0) {
        L.lessonHeight = std::clamp(L.lessonHeight + d / std::max(1.0f, r.mainH), 0.2f, 0.9f);
    }
    return r.mainH - (lessonH + kBar);
}

// The tables as tabs: only those a lesson stop wants; a lesson stop, an opened trace or a
// request (pendingTab) selects one.
void ShowSideTabs(AppState& state, const SideTab* firstWanted, float height) {
    ImGui::BeginChild("##tabs", ImVec2(0, height), false, ImGuiWindowFlags_NoScrollbar);
    // Narrower than every tab: the tabs scroll (arrows, and a list of them) instead of
    // cutting their labels.
    if (ImGui::BeginTabBar("##sidetabs", ImGuiTabBarFlags_FittingPolicyScroll |
                                             ImGuiTabBarFlags_TabListPopupButton)) {
        const bool traceOpened = studentTraceSelectTab(state);
        for (const SideTab& tab : kSideTabs) {
            if (tab.id && !lessonWantsPanel(state, tab.id)) continue;
            const bool select =
                (state.lessonPlayer.pendingTabSelect && &tab == firstWanted) ||
                (traceOpened && tab.id && std::string_view(tab.id) == "trace-compare") ||
                (tab.id && state.pendingTab == tab.id);
            const bool open =
                ImGui::BeginTabItem(tab.name, nullptr, select ? ImGuiTabItemFlags_SetSelected : 0);
            RecordItem(state, tab.title);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tab.title);
            if (open) {
                tab.show(state);
                ImGui::EndTabItem();
            }
        }
        ImGui::EndTabBar();
    }
    ImGui::EndChild();
}

// Right: the lesson (when one is open), the tables (tabs), the inspector. A lesson stop may
// name the panels it wants: only those show (lesson_player.h).
void ShowSideColumn(AppState& state, const Regions& r) {
    ImGui::BeginChild("##side", ImVec2(r.sideW, r.mainH), false, ImGuiWindowFlags_NoScrollbar);
    const float sideH = ShowLessonPane(state, r);
    const SideTab* firstWanted = nullptr;
    for (const SideTab& tab : kSideTabs) {
        if (!firstWanted && tab.id && lessonWantsPanel(state, tab.id)) firstWanted = &tab;
    }
    Layout& L = state.layout;
    const bool showInspector = lessonWantsPanel(state, "inspector");
    const float inspH =
        !showInspector ? 0.0f
        : firstWanted ? std::clamp(L.inspectorHeight * sideH, 80.0f, std::max(80.0f, sideH - 80.0f))
                      : sideH;
    if (firstWanted) ShowSideTabs(state, firstWanted, showInspector ? sideH - inspH - kBar : sideH);
    state.lessonPlayer.pendingTabSelect = false;
    state.pendingTab.clear();
    if (showInspector && firstWanted) {
        if (const float d = Splitter("##isplit", false, kBar, r.sideW); d != 0) {
            L.inspectorHeight =
                std::clamp(L.inspectorHeight - d / std::max(1.0f, sideH), 0.1f, 0.9f);
        }
    }
    if (showInspector) {
        ImGui::BeginChild("##inspector", ImVec2(0, 0), false);
        ShowInspector(state);
        ImGui::EndChild();
    }
    ImGui::EndChild();
}

// Bottom: the messages, under a splitter.
void ShowBottomStrip(AppState& state, const Regions& r) {
    Layout& L = state.layout;
    if (const float d = Splitter("##hsplit", false, kBar, r.avail.x); d != 0) {
        L.bottomHeight = std::clamp(L.bottomHeight - d / std::max(1.0f, r.avail.y), 0.05f, 0.6f);
    }
    ImGui::BeginChild("##bottom", ImVec2(0, 0), false);
    ShowMessages(state);
    ImGui::EndChild();
}

}  // namespace

void ShowApplication(AppState& state) {
    UpdateBeforeDrawing(state);
    BeginHostWindow();
    ShowMenuBar(state);
    if (slideMode(state)) {  // presentation with a lesson: the slide layout (lesson.cpp)
        ShowSlide(state);
        ImGui::End();
        if (state.showHelp) ShowHelp(state);
        ShowHistoryOffer(state);
        ShowFileDialogs(state);
        return;
    }
    ShowToolbar(state);
    ShowCaption(state);
    const Regions r = MeasureRegions(state);
    ShowLeftColumn(state, r);
    ImGui::SameLine(0, 0);
    if (const float d = Splitter("##vsplit", true, kBar, r.mainH); d != 0) {
        Layout& L = state.layout;
        L.rightWidth = std::clamp(L.rightWidth - d / std::max(1.0f, r.avail.x), 0.15f, 0.7f);
    }
    ImGui::SameLine(0, 0);
    ShowSideColumn(state, r);
    ShowBottomStrip(state, r);
    ImGui::End();

    if (state.showHelp) ShowHelp(state);
    ShowHistoryOffer(state);
    ShowFileDialogs(state);
}

void RecordItem(AppState& state, const char* name) {
    // Only the part a user can see and click: an item scrolled out of its window (or clipped by
    // it) is recorded clipped, or not at all.
    const ImVec2 clipMin = ImGui::GetWindowDrawList()->GetClipRectMin(),
                 clipMax = ImGui::GetWindowDrawList()->GetClipRectMax();
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const ImVec2 a(std::max(lo.x, clipMin.x), std::max(lo.y, clipMin.y)),
        b(std::min(hi.x, clipMax.x), std::min(hi.y, clipMax.y));
    if (a.x >= b.x || a.y >= b.y) {
        state.itemRects.erase(name);
        return;
    }
    state.itemRects[name] = {a.x, a.y, b.x, b.y};
}

void handleShortcuts(AppState& state) {
    const ImGuiIO& io = ImGui::GetIO();
    // A text field has the keyboard (or takes it back this frame, after Enter): every key is
    // typing, no shortcut fires.
    ExpressionState& ex = state.expressions;
    if (ex.refocusInput > 0 || ex.refocusWatch > 0) {
        ex.refocusInput = std::max(0, ex.refocusInput - 1);
        ex.refocusWatch = std::max(0, ex.refocusWatch - 1);
        return;
    }
    if (io.WantTextInput || ImGui::IsAnyItemActive()) return;
    auto pressed = [](int k) { return ImGui::IsKeyPressed(k, true); };
    auto once = [](int k) { return ImGui::IsKeyPressed(k, false); };
    Engine& e = state.engine;
    const bool ctrl = io.KeyCtrl, shift = io.KeyShift;

    if (once(key::kF1)) state.showHelp = !state.showHelp;
    if (once(key::kF12)) state.files.screenshotRequested = true;  // serviceCaptures writes it
    // Esc closes a popup first (the popup does it), then the help, then the selection.
    if (once(key::kEscape) && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) {
        if (state.showHelp)
            state.showHelp = false;
        else
            state.select(kNone);
    }
    if (ctrl) {
        if (once(key::letter('Z'))) shift ? state.redoEdit() : state.undoEdit();
        if (once(key::letter('Y'))) state.redoEdit();
        if (once(key::letter('Q'))) state.quitRequested = true;
        if (once(key::letter('S'))) state.files.dialog = FileState::Dialog::SaveSession;
        if (once(key::letter('O'))) state.files.dialog = FileState::Dialog::OpenFile;
        // Ctrl + arrows pan the canvas by a tenth of its size.
        View& v = state.view;
        const double step = 0.1 * std::min(v.size.x, v.size.y) / v.scale;
        if (pressed(key::kLeft)) v.center.x -= step;
        if (pressed(key::kRight)) v.center.x += step;
        if (pressed(key::kUp)) v.center.y += step;
        if (pressed(key::kDown)) v.center.y -= step;
        return;
    }
    // Stepping: arrows and presentation clickers (Page Up / Page Down); on slides the clickers
    // move between the lesson's stops.
    const bool slides = slideMode(state);
    if (slides && once(key::kPageDown)) goToStop(state, state.lessonPlayer.progress.stop + 1);
    if (slides && once(key::kPageUp) && state.lessonPlayer.progress.stop > 0)
        goToStop(state, state.lessonPlayer.progress.stop - 1);
    if (pressed(key::kRight) || (!slides && pressed(key::kPageDown))) {
        state.run.running = false;
        shift ? e.forwardInsertion() : e.forward();
    }
    if (pressed(key::kLeft) || (!slides && pressed(key::kPageUp))) {
        state.run.running = false;
        shift ? e.backInsertion() : e.back();
    }
    if (once(key::kHome)) {
        state.run.running = false;
        e.toStart();
    }
    if (once(key::kEnd)) state.run.runToEnd();
    if (once(key::kSpace)) state.run.running = !state.run.running;
    // Corner operators on the selection.
    for (char op : {'n', 'p', 'o', 'l', 'r', 's', 'u'}) {
        if (pressed(key::letter(op))) state.moveSelection(op);
    }
    // View and overlays.
    if (once(key::letter('F'))) state.fitPending = true;
    if (once(key::letter('V'))) state.overlays.voronoi = !state.overlays.voronoi;
    if (once(key::letter('C'))) state.overlays.circumcircles = !state.overlays.circumcircles;
    if (once(key::letter('L'))) state.overlays.legend = !state.overlays.legend;
    if (once(key::letter('G'))) state.snapToGrid = !state.snapToGrid;
    if (pressed(key::kEqual) || pressed(key::kKpAdd))
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 1.25);
    if (pressed(key::kMinus) || pressed(key::kKpSubtract))
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 0.8);
}

}  // namespace dlab::ui
