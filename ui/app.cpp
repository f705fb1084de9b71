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

}  // namespace

void ShowApplication(AppState& state) {
    ImGuiIO& io = ImGui::GetIO();
    handleShortcuts(state);
    advanceRun(state, io.DeltaTime);
    updateDebugPanels(state);  // watches (may pause the run), checks, autosave
    if (std::string notice = state.engine.takeNotice(); !notice.empty()) {
        state.run.running = false;
        state.log(Message::Level::Warning, notice);
    }

    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos);
    ImGui::SetNextWindowSize(vp->WorkSize);
    const ImGuiWindowFlags hostFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                       ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_MenuBar |
                                       ImGuiWindowFlags_NoBringToFrontOnFocus |
                                       ImGuiWindowFlags_NoScrollWithMouse;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 4));
    ImGui::Begin("Delaunay Lab", nullptr, hostFlags);
    ImGui::PopStyleVar();
    ShowMenuBar(state);
    if (slideMode(state)) {  // presentation with a lesson: the slide layout (lesson.cpp)
        ShowSlide(state);
        ImGui::End();
        if (state.showHelp) ShowHelp(state);
        ShowFileDialogs(state);
        return;
    }
    ShowToolbar(state);
    ShowCaption(state);

    const float kBar = 6.0f;
    Layout& L = state.layout;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float bottomH = std::clamp(L.bottomHeight * avail.y, 40.0f, avail.y * 0.6f);
    const float mainH = std::max(100.0f, avail.y - bottomH - kBar);
    const float sideW = state.presentation
                            ? std::clamp(L.rightWidth * avail.x, 0.0f, avail.x * 0.7f)
                            : std::clamp(L.rightWidth * avail.x, 220.0f, avail.x * 0.7f);
    const float canvasW = std::max(100.0f, avail.x - sideW - kBar);

    // ---- Left: canvas and timeline -------------------------------------------------------------
    ImGui::BeginChild("##left", ImVec2(canvasW, mainH), false,
                      ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
    ShowCanvas(state);
    DrawDebugOverlays(state);
    ShowCanvasNotice(state);
    ShowTimeline(state);
    ImGui::EndChild();
    ImGui::SameLine(0, 0);
    if (const float d = Splitter("##vsplit", true, kBar, mainH); d != 0) {
        L.rightWidth = std::clamp(L.rightWidth - d / std::max(1.0f, avail.x), 0.15f, 0.7f);
    }
    ImGui::SameLine(0, 0);

    // ---- Right: the lesson (when one is open), tables (tabs), inspector ------------------------
    // A lesson stop may name the panels it wants: only those show (lesson_player.h).
    ImGui::BeginChild("##side", ImVec2(sideW, mainH), false, ImGuiWindowFlags_NoScrollbar);
    float sideH = mainH;
    if (state.lessonPlayer.lesson) {
        const float lessonH = std::clamp(L.lessonHeight * mainH, 120.0f, mainH - 60.0f);
        ImGui::BeginChild("##lesson", ImVec2(0, lessonH), true);
        ShowLesson(state);
        ImGui::EndChild();
        if (const float d = Splitter("##lsplit", false, kBar, sideW); d != 0) {
            L.lessonHeight = std::clamp(L.lessonHeight + d / std::max(1.0f, mainH), 0.2f, 0.9f);
        }
        sideH -= lessonH + kBar;
    }
    const SideTab* firstWanted = nullptr;
    for (const SideTab& tab : kSideTabs) {
        if (!firstWanted && tab.id && lessonWantsPanel(state, tab.id)) firstWanted = &tab;
    }
    const bool showInspector = lessonWantsPanel(state, "inspector");
    const float inspH =
        !showInspector ? 0.0f
        : firstWanted ? std::clamp(L.inspectorHeight * sideH, 80.0f, std::max(80.0f, sideH - 80.0f))
                      : sideH;
    if (firstWanted) {
        ImGui::BeginChild("##tabs", ImVec2(0, showInspector ? sideH - inspH - kBar : sideH), false,
                          ImGuiWindowFlags_NoScrollbar);
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
                const bool open = ImGui::BeginTabItem(tab.name, nullptr,
                                                      select ? ImGuiTabItemFlags_SetSelected : 0);
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
    state.lessonPlayer.pendingTabSelect = false;
    state.pendingTab.clear();
    if (showInspector && firstWanted) {
        if (const float d = Splitter("##isplit", false, kBar, sideW); d != 0) {
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

    // ---- Bottom: messages ---------------------------------------------------------------------
    if (const float d = Splitter("##hsplit", false, kBar, avail.x); d != 0) {
        L.bottomHeight = std::clamp(L.bottomHeight - d / std::max(1.0f, avail.y), 0.05f, 0.6f);
    }
    ImGui::BeginChild("##bottom", ImVec2(0, 0), false);
    ShowMessages(state);
    ImGui::EndChild();
    ImGui::End();

    if (state.showHelp) ShowHelp(state);
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
    if (once(key::letter('G'))) state.snapToGrid = !state.snapToGrid;
    if (pressed(key::kEqual) || pressed(key::kKpAdd))
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 1.25);
    if (pressed(key::kMinus) || pressed(key::kKpSubtract))
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 0.8);
}

}  // namespace dlab::ui
