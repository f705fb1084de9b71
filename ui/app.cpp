// The application's layout (Debian's ImGui 1.86 has no docking): one host window filling the
// display, with a menu bar, the toolbar and caption, the canvas in the middle, the tables and
// inspector in a side column, messages below; splitters between them, remembered in Layout.
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace dlab::ui {

namespace {

// Short labels, so that every tab shows whole in a 1600-pixel window, and shorter ones when the
// column is narrower (1280 x 720); the full title in the tooltip (and as the name tests and
// lessons find it by).
const SideTab kSideTabs[] = {
    {"Corners", ShowCornerTable, "corner-table", "Corner table", "Corners"},
    {"G", ShowVertexTable, "vertex-table", "G (vertices)", "G"},
    {"Expressions", ShowExpressions, "expressions", "Expressions", "Expr"},
    {"Predicates", ShowPredicates, "predicates", "Predicates", "Pred"},
    {"ID buffer", ShowIdBuffer, "idbuffer", "ID buffer", "IDs"},
    {"Statistics", ShowStatistics, "statistics", "Statistics", "Stats"},
    {"Trace", ShowTraceCompare, "trace-compare", "Student trace", "Trace"},
    {"Check", ShowCheck, "check", "Check the mesh", "Check"},
};

// A lesson shows the tabs it names; the Check tab is there while a mesh made elsewhere is open.
bool TabShown(const AppState& state, const SideTab& tab) {
    if (tab.id && std::string_view(tab.id) == "check" && !state.meshCheck.open) return false;
    return !tab.id || lessonWantsPanel(state, tab.id);
}

// Whether the tabs' labels (those shown) fit the column whole, with the tab list's button.
bool TabLabelsFit(const AppState& state) {
    const ImGuiStyle& style = ImGui::GetStyle();
    float width = ImGui::GetFrameHeight();  // the tab list button
    for (const SideTab& tab : kSideTabs) {
        if (!TabShown(state, tab)) continue;
        width +=
            ImGui::CalcTextSize(tab.name).x + 2 * style.FramePadding.x + style.ItemInnerSpacing.x;
    }
    return width <= ImGui::GetContentRegionAvail().x;
}

}  // namespace

std::vector<std::string> sideTabIds() {
    std::vector<std::string> ids;
    for (const SideTab& tab : kSideTabs) ids.emplace_back(tab.id);
    return ids;
}

namespace {

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
void BeginHostWindow(bool menuBar) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos);
    ImGui::SetNextWindowSize(vp->WorkSize);
    const ImGuiWindowFlags hostFlags =
        ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
        (menuBar ? ImGuiWindowFlags_MenuBar : 0) | ImGuiWindowFlags_NoBringToFrontOnFocus |
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
    // The splitter's share, or more when the stop's text and question need it (a short window):
    // the question is never below the fold while the tables keep a few rows.
    const float wanted = std::min(state.lessonPlayer.paneHeightWanted, r.mainH - 140.0f);
    const float lessonH =
        std::clamp(std::max(L.lessonHeight * r.mainH, wanted), 120.0f, r.mainH - 60.0f);
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
        const bool whole = TabLabelsFit(state);
        for (const SideTab& tab : kSideTabs) {
            if (!TabShown(state, tab)) continue;
            const bool select =
                (state.lessonPlayer.pendingTabSelect && &tab == firstWanted) ||
                (traceOpened && tab.id && std::string_view(tab.id) == "trace-compare") ||
                (tab.id && state.pendingTab == tab.id);
            // One id whichever label shows: the selected tab stays selected across a resize.
            const std::string label =
                std::string(whole ? tab.name : tab.shortName) + "###" + tab.title;
            const bool open = ImGui::BeginTabItem(label.c_str(), nullptr,
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

// The inspector's height with a corner selected: its title and buttons, the ten rows of its
// table (c, t, v, n, p, o, l, r, s, u), the vertex's coordinates and the last move.
float InspectorHeightNeeded() {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float row = ImGui::GetTextLineHeight() + 2 * style.CellPadding.y;
    return ImGui::GetFrameHeightWithSpacing() + 10 * row +
           2 * ImGui::GetTextLineHeightWithSpacing() + style.ItemSpacing.y;
}

// Right: the lesson (when one is open), the tables (tabs), the inspector. A lesson stop may
// name the panels it wants: only those show (lesson_player.h).
void ShowSideColumn(AppState& state, const Regions& r) {
    ImGui::BeginChild("##side", ImVec2(r.sideW, r.mainH), false, ImGuiWindowFlags_NoScrollbar);
    const float sideH = ShowLessonPane(state, r);
    const SideTab* firstWanted = nullptr;
    for (const SideTab& tab : kSideTabs) {
        if (!firstWanted && tab.id && TabShown(state, tab)) firstWanted = &tab;
    }
    Layout& L = state.layout;
    const bool showInspector = lessonWantsPanel(state, "inspector");
    // With a corner selected the inspector gets at least the rows it shows (t to u, s and u
    // included), while the tables above keep 140 pixels: a short window need not scroll it.
    float inspShare = L.inspectorHeight * sideH;
    if (state.selection.corner != kNone)
        inspShare = std::max(inspShare, std::min(InspectorHeightNeeded(), sideH - 140.0f));
    const float inspH = !showInspector ? 0.0f
                        : firstWanted ? std::clamp(inspShare, 80.0f, std::max(80.0f, sideH - 80.0f))
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
    const bool menus = !(state.handoutSlides && slideMode(state));  // a handout's picture: none
    BeginHostWindow(menus);
    if (menus) ShowMenuBar(state);
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

namespace {

// Ctrl + a key: undo/redo, quit, save, open; Ctrl + arrows pan the canvas by a tenth of its size.
void ctrlShortcut(AppState& state, const KeyPress& k) {
    switch (k.key) {
        case key::letter('Z'): k.shift ? state.redoEdit() : state.undoEdit(); return;
        case key::letter('Y'): state.redoEdit(); return;
        case key::letter('Q'): state.quitRequested = true; return;
        case key::letter('S'): state.files.dialog = FileState::Dialog::SaveSession; return;
        case key::letter('O'): state.files.dialog = FileState::Dialog::OpenFile; return;
        default: break;
    }
    View& v = state.view;
    const double step = 0.1 * std::min(v.size.x, v.size.y) / v.scale;
    if (k.key == key::kLeft) v.center.x -= step;
    if (k.key == key::kRight) v.center.x += step;
    if (k.key == key::kUp) v.center.y += step;
    if (k.key == key::kDown) v.center.y -= step;
}

// Stepping: arrows and presentation clickers (Page Up / Page Down); on slides the clickers move
// between the lesson's stops. True when the key was one of them.
bool stepShortcut(AppState& state, const KeyPress& k) {
    Engine& e = state.engine;
    const bool slides = slideMode(state);
    if (slides && k.key == key::kPageDown) {
        goToSlide(state, slideIndex(state) + 1);  // a track's crosses into its next lesson
    } else if (slides && k.key == key::kPageUp) {
        if (slideIndex(state) > 0) goToSlide(state, slideIndex(state) - 1);
    } else if (k.key == key::kRight || k.key == key::kPageDown) {
        state.run.running = false;
        k.shift ? e.forwardInsertion() : e.forward();
    } else if (k.key == key::kLeft || k.key == key::kPageUp) {
        state.run.running = false;
        k.shift ? e.backInsertion() : e.back();
    } else if (k.key == key::kHome) {
        state.run.running = false;
        e.toStart();
    } else if (k.key == key::kEnd) {
        state.run.runToEnd();
    } else if (k.key == key::kSpace) {
        state.run.running = !state.run.running;
    } else {
        return false;
    }
    return true;
}

// A key without Ctrl: help, screenshot, Esc, stepping, corner operators, view and overlays.
void plainShortcut(AppState& state, const KeyPress& k) {
    if (k.key == key::kF1) state.showHelp = !state.showHelp;
    if (k.key == key::kF12) state.files.screenshotRequested = true;  // serviceCaptures writes it
    // Esc closes a popup first (the popup does it), then the help, then the selection.
    if (k.key == key::kEscape && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) {
        if (state.showHelp)
            state.showHelp = false;
        else if (state.toolFirstVertex != kNone)
            state.toolFirstVertex = kNone;  // a segment half picked
        else
            state.select(kNone);
    }
    if (k.key == key::kDelete && !slideMode(state)) RemoveSelectedVertex(state);
    if (stepShortcut(state, k)) return;
    for (char op : {'n', 'p', 'o', 'l', 'r', 's', 'u'}) {
        if (k.key == key::letter(op)) state.moveSelection(op);
    }
    if (k.key == key::letter('F')) state.fitPending = true;
    if (k.key == key::letter('V')) state.overlays.voronoi = !state.overlays.voronoi;
    if (k.key == key::letter('C')) state.overlays.circumcircles = !state.overlays.circumcircles;
    if (k.key == key::letter('L')) state.overlays.legend = !state.overlays.legend;
    if (k.key == key::letter('G')) state.snapToGrid = !state.snapToGrid;
    if (k.key == key::kEqual || k.key == key::kKpAdd)
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 1.25);
    if (k.key == key::kMinus || k.key == key::kKpSubtract)
        state.view.zoomAt(state.view.origin + state.view.size * 0.5, 0.8);
}

}  // namespace

void handleShortcuts(AppState& state) {
    // Every press since the last frame, in order (ui/platform/keys.h): a tap whose release came
    // before this frame counts as much as a held key, and auto-repeat steps on.
    const std::vector<KeyPress> presses = takeKeyPresses();
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
    for (const KeyPress& k : presses) k.ctrl ? ctrlShortcut(state, k) : plainShortcut(state, k);
}

}  // namespace dlab::ui
